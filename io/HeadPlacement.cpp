#include "io/HeadPlacement.h"
#include "io/RegularFile.h"
#include "sim/util/NumberText.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace wisp::io {

namespace {

std::string metresText(double metres)
{
    return formatNumber(metres) + " m";
}

// The unit whose metres-per-unit is exactly `scale`, or Auto.
LengthUnit unitOfScale(float scale)
{
    for (LengthUnit unit : { LengthUnit::Millimetres, LengthUnit::Centimetres, LengthUnit::Metres })
        if (scale == metresPerUnit(unit))
            return unit;
    return LengthUnit::Auto;
}

bool skullSized(double widthMetres)
{
    return widthMetres >= skullMinWidthMetres && widthMetres < skullMaxWidthMetres;
}

// Metres per unit as the decimal it stands for: 0.01f is not exactly 0.01, and the size
// boundaries are compared exactly.
double exactMetresPerUnit(LengthUnit unit)
{
    switch (unit) {
    case LengthUnit::Millimetres:
        return 0.001;
    case LengthUnit::Centimetres:
        return 0.01;
    case LengthUnit::Metres:
        return 1.0;
    case LengthUnit::Auto:
        break;
    }
    return 0.0;
}

} // namespace

float metresPerUnit(LengthUnit unit)
{
    switch (unit) {
    case LengthUnit::Millimetres:
        return 0.001f;
    case LengthUnit::Centimetres:
        return 0.01f;
    case LengthUnit::Metres:
        return 1.0f;
    case LengthUnit::Auto:
        break;
    }
    return 0.0f;
}

const char* unitName(LengthUnit unit)
{
    switch (unit) {
    case LengthUnit::Millimetres:
        return "millimetres";
    case LengthUnit::Centimetres:
        return "centimetres";
    case LengthUnit::Metres:
        return "metres";
    case LengthUnit::Auto:
        break;
    }
    return "auto";
}

HeadPlacement placeHead(TriangleMesh& mesh, LengthUnit unit, float explicitScale)
{
    HeadPlacementSettings settings;
    settings.unit = unit;
    settings.explicitScale = explicitScale;
    return placeHead(mesh, settings);
}

HeadPlacement placeHead(TriangleMesh& mesh, const HeadPlacementSettings& settings)
{
    HeadPlacement placement;
    if (mesh.positions.empty()) {
        placement.note = "the mesh has no vertices; nothing to place";
        return placement;
    }

    // Which way is up: as named, or from the shape, or the file's own axes.
    std::string whyNotFound;
    if (settings.up) {
        placement.up = *settings.up;
        placement.front = defaultFront(*settings.up);
        placement.orientation = std::string(axisName(placement.up)) + " up as chosen";
    } else {
        const HeadOrientation found = detectHeadOrientation(mesh.positions);
        placement.upFromShape = found.found;
        if (found.found) {
            placement.up = found.up;
            placement.front = found.front;
        }
        placement.orientation = found.found ? std::string(axisName(found.up)) + " up, face " + axisName(found.front)
                + " (found from its shape: " + found.reason + ")"
                                            : "kept the file's +Y up: " + found.reason;
        if (!found.found)
            whyNotFound = found.reason;
    }
    std::vector<glm::vec3> upright(mesh.positions.size());
    for (std::size_t i = 0; i < upright.size(); ++i)
        upright[i] = orient(mesh.positions[i], placement.up, placement.front);

    // Bounds and skull width in file units, after the turn.
    Aabb box{ upright.front(), upright.front() };
    for (const glm::vec3& p : upright) {
        box.min = glm::min(box.min, p);
        box.max = glm::max(box.max, p);
    }
    const glm::vec3 size = box.size();
    const float largest = std::max({ size.x, size.y, size.z });
    // A flat mesh (a mask, a plane seen edge on) may have no width at the top; its largest extent stands in.
    float skull = skullWidth(upright);
    if (!(skull > 1e-6f * largest))
        skull = largest;

    const bool explicitGiven = settings.explicitScale > 0.0f && std::isfinite(settings.explicitScale);
    std::vector<std::string> notes;
    if (!explicitGiven && settings.explicitScale != 0.0f)
        notes.push_back(
            "ignored the scale " + formatNumber(settings.explicitScale) + " (it must be a positive number)");

    if (explicitGiven) {
        placement.scale = settings.explicitScale;
        placement.unit = unitOfScale(settings.explicitScale);
    } else if (settings.unit != LengthUnit::Auto) {
        placement.scale = metresPerUnit(settings.unit);
        placement.unit = settings.unit;
    } else if (!(largest > 0.0f)) {
        placement.scale = 1.0f;
        placement.unit = LengthUnit::Metres;
        notes.push_back("the mesh has no extent, so its unit cannot be guessed; left at metres");
    } else {
        placement.unit = LengthUnit::Auto;
        for (LengthUnit candidate : { LengthUnit::Millimetres, LengthUnit::Centimetres, LengthUnit::Metres })
            if (skullSized(double{ skull } * exactMetresPerUnit(candidate))) {
                placement.unit = candidate;
                placement.scale = metresPerUnit(candidate);
            }
        if (placement.unit == LengthUnit::Auto) {
            placement.scale = static_cast<float>(fittedSkullWidthMetres / double{ skull });
            placement.scaledToFit = true;
            notes.push_back("the skull is " + formatNumber(skull) + " units wide, which is no skull width ("
                + metresText(skullMinWidthMetres) + " to under " + metresText(skullMaxWidthMetres)
                + ") in millimetres, centimetres or metres; scaled it to " + metresText(fittedSkullWidthMetres)
                + " wide");
        }
    }
    placement.skullWidthMetres = skull * placement.scale;

    // A unit the artist chose (or a factor) may still make an odd head; say so, do not undo it.
    if (explicitGiven || settings.unit != LengthUnit::Auto) {
        const double widthMetres = double{ skull } * double{ placement.scale };
        if (largest > 0.0f && !skullSized(widthMetres))
            notes.push_back("at this scale the skull is " + metresText(widthMetres) + " wide; skulls are usually "
                + metresText(skullMinWidthMetres) + " to " + metresText(skullMaxWidthMetres));
    }
    if (!whyNotFound.empty())
        notes.push_back("could not tell which way is up (" + whyNotFound
            + "); kept the file's +Y up: choose the up axis if the head lies on its side");

    for (const std::string& note : notes)
        placement.note += (placement.note.empty() ? "" : "; ") + note;
    placement.offset = -box.center() * placement.scale;
    for (std::size_t i = 0; i < upright.size(); ++i)
        mesh.positions[i] = upright[i] * placement.scale + placement.offset;
    return placement;
}

std::string checkPlacedHead(const TriangleMesh& placed)
{
    if (std::string problem = validateMesh(placed); !problem.empty())
        return problem;
    const glm::vec3 size = boundsOf(placed).size();
    char extents[96];
    std::snprintf(extents, sizeof extents, "%.4g x %.4g x %.4g m", size.x, size.y, size.z);
    const double largest = std::max({ double{ size.x }, double{ size.y }, double{ size.z } });
    if (!(largest <= headMaxPlacedExtentMetres))
        return std::string("the placed head is ") + extents + ", more than " + metresText(headMaxPlacedExtentMetres)
            + " at its largest: a stray vertex far from the others, or the wrong unit (--scale / Head Scale)";
    static const char* const axisNames[] = { "x", "y", "z" };
    for (int axis = 0; axis < 3; ++axis)
        if (!(double{ size[axis] } >= headMinAxisExtentMetres))
            return std::string("the placed head is ") + extents + ": flat along " + axisNames[axis] + " (less than "
                + metresText(headMinAxisExtentMetres)
                + "); a head needs depth on every axis to have an inside the hair can collide with";
    return {};
}

void applyPlacement(TriangleMesh& mesh, const HeadPlacement& placement)
{
    applyPlacement(std::span<glm::vec3>(mesh.positions), placement);
}

void applyPlacement(std::span<glm::vec3> points, const HeadPlacement& placement)
{
    for (glm::vec3& p : points)
        p = orient(p, placement.up, placement.front) * placement.scale + placement.offset;
}

std::string describePlacement(const HeadPlacement& placement)
{
    std::string text = "imported at \u00D7" + formatNumber(placement.scale) + " (";
    if (placement.unit != LengthUnit::Auto)
        text += unitName(placement.unit);
    else if (placement.scaledToFit)
        text += "scaled to a " + metresText(fittedSkullWidthMetres) + " wide skull";
    else
        text += "chosen scale";
    text += ")";
    if (placement.turned() || placement.upFromShape)
        text += std::string(", ") + axisName(placement.up) + " up, face " + axisName(placement.front)
            + (placement.upFromShape ? " (from its shape)" : "");
    return text;
}

bool formatFixesUpAxis(const std::string& path)
{
    const std::string ext = lowerExtension(path);
    return ext == "gltf" || ext == "glb";
}

} // namespace wisp::io
