#include "io/HeadPlacement.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace wisp::io {

namespace {

// The Z-up to Y-up turn: -90 degrees about +X. A proper rotation, so winding is kept.
glm::vec3 turnUpright(const glm::vec3& p)
{
    return {p.x, p.z, -p.y};
}

std::string formatNumber(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string metresText(double metres)
{
    return formatNumber(metres) + " m";
}

// The unit whose metres-per-unit is exactly `scale`, or Auto.
LengthUnit unitOfScale(float scale)
{
    for (LengthUnit unit : {LengthUnit::Millimetres, LengthUnit::Centimetres, LengthUnit::Metres})
        if (scale == metresPerUnit(unit))
            return unit;
    return LengthUnit::Auto;
}

bool headSized(double extentMetres)
{
    return extentMetres >= headMinExtentMetres && extentMetres < headMaxExtentMetres;
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
    placement.rotatedUpright = settings.zUp;
    if (mesh.positions.empty()) {
        placement.note = "the mesh has no vertices; nothing to place";
        return placement;
    }

    // Bounds in file units, after the optional turn (which only permutes and negates axes).
    Aabb box = boundsOf(mesh);
    if (settings.zUp)
        box = Aabb{glm::vec3(box.min.x, box.min.z, -box.max.y), glm::vec3(box.max.x, box.max.z, -box.min.y)};
    const glm::vec3 size = box.size();
    const float largest = std::max({size.x, size.y, size.z});

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
        for (LengthUnit candidate : {LengthUnit::Millimetres, LengthUnit::Centimetres, LengthUnit::Metres})
            if (headSized(double{largest} * exactMetresPerUnit(candidate))) {
                placement.unit = candidate;
                placement.scale = metresPerUnit(candidate);
            }
        if (placement.unit == LengthUnit::Auto) {
            // Height, not the largest extent, is what the artist will check; a flat mesh (a
            // mask, a plane) has none, so its largest extent stands in.
            const float height = size.y > 1e-6f * largest ? size.y : largest;
            placement.scale = static_cast<float>(fittedHeadHeightMetres / double{height});
            placement.scaledToFit = true;
            notes.push_back("the mesh is " + formatNumber(largest) + " units at its largest, which is no head size ("
                + metresText(headMinExtentMetres) + " to under " + metresText(headMaxExtentMetres)
                + ") in millimetres, centimetres or metres; scaled it to " + metresText(fittedHeadHeightMetres)
                + " tall");
        }
    }

    // A unit the artist chose (or a factor) may still make an odd head; say so, do not undo it.
    if (explicitGiven || settings.unit != LengthUnit::Auto) {
        const double largestMetres = double{largest} * double{placement.scale};
        if (largest > 0.0f && !headSized(largestMetres))
            notes.push_back("at this scale the head is " + metresText(largestMetres)
                + " at its largest; heads are usually " + metresText(headMinExtentMetres) + " to "
                + metresText(headMaxExtentMetres));
    }

    for (const std::string& note : notes)
        placement.note += (placement.note.empty() ? "" : "; ") + note;
    placement.offset = -box.center() * placement.scale;
    applyPlacement(mesh, placement);
    return placement;
}

std::string checkPlacedHead(const TriangleMesh& placed)
{
    if (std::string problem = validateMesh(placed); !problem.empty())
        return problem;
    const glm::vec3 size = boundsOf(placed).size();
    char extents[96];
    std::snprintf(extents, sizeof extents, "%.4g x %.4g x %.4g m", size.x, size.y, size.z);
    const double largest = std::max({double{size.x}, double{size.y}, double{size.z}});
    if (!(largest <= headMaxPlacedExtentMetres))
        return std::string("the placed head is ") + extents + ", more than " + metresText(headMaxPlacedExtentMetres) +
               " at its largest: a stray vertex far from the others, or the wrong unit (--scale / Head Scale)";
    static const char* const axisNames[] = {"x", "y", "z"};
    for (int axis = 0; axis < 3; ++axis)
        if (!(double{size[axis]} >= headMinAxisExtentMetres))
            return std::string("the placed head is ") + extents + ": flat along " + axisNames[axis] +
                   " (less than " + metresText(headMinAxisExtentMetres) +
                   "); a head needs depth on every axis to have an inside the hair can collide with";
    return {};
}

void applyPlacement(TriangleMesh& mesh, const HeadPlacement& placement)
{
    for (glm::vec3& p : mesh.positions) {
        const glm::vec3 upright = placement.rotatedUpright ? turnUpright(p) : p;
        p = upright * placement.scale + placement.offset;
    }
}

std::string describePlacement(const HeadPlacement& placement)
{
    std::string text = "imported at \u00D7" + formatNumber(placement.scale) + " (";
    if (placement.unit != LengthUnit::Auto)
        text += unitName(placement.unit);
    else if (placement.scaledToFit)
        text += "scaled to " + metresText(fittedHeadHeightMetres) + " tall";
    else
        text += "chosen scale";
    text += ")";
    if (placement.rotatedUpright)
        text += ", turned Z-up to Y-up";
    return text;
}

bool formatFixesUpAxis(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(
        ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".gltf" || ext == ".glb";
}

} // namespace wisp::io
