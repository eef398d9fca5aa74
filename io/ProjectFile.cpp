#include "io/ProjectFile.h"
#include "io/HeadPlacement.h"
#include "io/JsonErrors.h"
#include "io/MeshReader.h"
#include "io/MotionJson.h"
#include "io/ProjectFileShared.h"

#include "io/AtomicFile.h"
#include "io/Base64.h"
#include "io/HeadPlacement.h"
#include "io/PresetFile.h"
#include "io/RegularFile.h"

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

namespace wisp::io {

using nlohmann::json;
using nlohmann::ordered_json;
namespace fs = std::filesystem;
using namespace detail;

namespace project_detail {

fs::path projectFolder(const std::string& projectPath)
{
    std::error_code error;
    fs::path absolute = fs::absolute(projectPath, error);
    if (error)
        absolute = projectPath;
    return absolute.lexically_normal().parent_path();
}

fs::path resolveAgainst(const fs::path& folder, const std::string& source)
{
    const fs::path path(source);
    return (path.is_absolute() ? path : folder / path).lexically_normal();
}

std::string regionPath(std::size_t index)
{
    return "regions[" + std::to_string(index) + "]";
}
std::string stylePath(std::size_t index)
{
    return "style[" + std::to_string(index) + "]";
}

bool isUnitColour(const glm::vec3& c)
{
    for (int i = 0; i < 3; ++i)
        if (!(c[i] >= 0.0f && c[i] <= 1.0f)) // also false for NaN
            return false;
    return true;
}

void checkProject(const Project& project)
{
    if (!std::isfinite(project.headImportScale) || project.headImportScale <= 0.0f)
        throw Refusal{ "head.import_scale", "the import scale must be a positive number" };
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(project.headImportOffset[i]))
            throw Refusal{ "head.import_offset", "expected 3 finite numbers" };
    if (!project.headEmbedded && project.headSource.empty())
        throw Refusal{ "head.source", "a head that is not stored in the project needs the file it comes from" };
    const std::size_t vertexCount = project.head.vertexCount();
    for (std::size_t t = 0; t < project.head.triangles.size(); ++t)
        for (int corner = 0; corner < 3; ++corner)
            if (project.head.triangles[t][corner] >= vertexCount)
                throw Refusal{ "head.triangles",
                    "triangle " + std::to_string(t) + " refers to vertex "
                        + std::to_string(project.head.triangles[t][corner]) + "; the head has "
                        + std::to_string(vertexCount) };
    if (std::string error = validateMesh(project.head); !error.empty())
        throw Refusal{ "head", error };

    if (project.regions.size() > kMaxRegions)
        throw Refusal{ "regions",
            std::to_string(project.regions.size()) + " regions; at most " + std::to_string(kMaxRegions)
                + " are allowed" };
    std::map<std::uint32_t, std::size_t> indexOfId;
    for (std::size_t i = 0; i < project.regions.size(); ++i) {
        const GrowthRegion& region = project.regions[i];
        const std::string path = regionPath(i);
        if (region.id == kNoSolo)
            throw Refusal{ path + ".id", std::to_string(region.id) + " is reserved (it means \"no region\")" };
        if (const auto [it, added] = indexOfId.emplace(region.id, i); !added)
            throw Refusal{ path + ".id",
                std::to_string(region.id) + " is already the id of " + regionPath(it->second) };
        if (region.name.size() > kMaxNameBytes)
            throw Refusal{ path + ".name",
                "the name is " + std::to_string(region.name.size()) + " bytes long; at most "
                    + std::to_string(kMaxNameBytes) + " are allowed" };
        if (region.weights.size() != vertexCount)
            throw Refusal{ path + ".weights",
                std::to_string(region.weights.size()) + " weights for a head of " + std::to_string(vertexCount)
                    + " vertices" };
        for (std::size_t v = 0; v < region.weights.size(); ++v)
            if (const float w = region.weights[v]; !(w >= 0.0f && w <= 1.0f))
                throw Refusal{ path + ".weights",
                    "the weight of vertex " + std::to_string(v) + " is " + std::to_string(w) + "; weights are 0..1" };
        if (!isUnitColour(region.rootColour))
            throw Refusal{ path + ".root_colour", "expected 3 numbers 0..1" };
        if (!isUnitColour(region.tipColour))
            throw Refusal{ path + ".tip_colour", "expected 3 numbers 0..1" };
    }
    if (project.soloRegion != kNoSolo && !indexOfId.contains(project.soloRegion))
        throw Refusal{ "solo_region", std::to_string(project.soloRegion) + " is the id of no region" };

    if (std::string e = project.motion.validate(); !e.empty())
        throw Refusal{ "motion", e };
    if (std::string e = validateBakeRange(project.timeline); !e.empty())
        throw Refusal{ "timeline", e };
    if (!(project.displayDensity >= kMinDisplayDensity && project.displayDensity <= kMaxDisplayDensity))
        throw Refusal{ "display_density", "the display density must be 0.25 to 4" };
    const CameraState& camera = project.camera;
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(camera.pivot[i]))
            throw Refusal{ "camera.pivot", "expected 3 finite numbers" };
    if (!std::isfinite(camera.yawRadians))
        throw Refusal{ "camera.yaw_radians", "not a finite number" };
    if (!std::isfinite(camera.pitchRadians))
        throw Refusal{ "camera.pitch_radians", "not a finite number" };
    if (!std::isfinite(camera.distanceMetres) || camera.distanceMetres <= 0.0f)
        throw Refusal{ "camera.distance_metres", "the distance must be a positive number" };
    if (!(camera.fovYDegrees > 0.0f && camera.fovYDegrees < 180.0f))
        throw Refusal{ "camera.fov_y_degrees", "the field of view must be between 0 and 180 degrees" };

    // Indexed as the file writes them: entries with nothing changed are left out.
    std::size_t styleIndex = 0;
    for (const auto& [identity, style] : project.style) {
        if (style.isDefault())
            continue;
        if (std::string error = validateStrandStyle(identity, style); !error.empty())
            throw Refusal{ stylePath(styleIndex), error };
        ++styleIndex;
    }
}

} // namespace project_detail

using namespace project_detail;

std::string projectToJson(const Project& project, const std::string& projectPath)
{
    const fs::path folder = projectFolder(projectPath);
    ordered_json root;
    root["format"] = "wisp-project";
    root["version"] = kProjectVersion;

    ordered_json head;
    if (project.headSource.empty()) {
        head["source"] = "";
        head["absolute_source"] = "";
    } else {
        const fs::path absolute = resolveAgainst(folder, project.headSource);
        const fs::path relative = absolute.lexically_relative(folder);
        head["source"] = relative.empty() ? absolute.string() : relative.string();
        head["absolute_source"] = absolute.string();
    }
    head["embedded"] = project.headEmbedded;
    head["import_scale"] = shortestDoubleForFloat(project.headImportScale);
    head["import_offset"] = vec3ToJson(project.headImportOffset);
    head["import_up"] = axisName(project.headImportUp);
    head["import_front"] = axisName(project.headImportFront);
    head["vertex_count"] = project.head.vertexCount();
    head["triangle_count"] = project.head.triangleCount();
    if (project.headEmbedded) {
        std::vector<float> positions;
        positions.reserve(3 * project.head.vertexCount());
        for (const glm::vec3& p : project.head.positions)
            positions.insert(positions.end(), { p.x, p.y, p.z });
        std::vector<std::uint32_t> indices;
        indices.reserve(3 * project.head.triangleCount());
        for (const glm::uvec3& t : project.head.triangles)
            indices.insert(indices.end(), { t.x, t.y, t.z });
        head["positions"] = encodeFloat32Array(positions);
        head["triangles"] = encodeUint32Array(indices);
    }
    root["head"] = std::move(head);

    ordered_json parameters = ordered_json::object();
    for (const ParameterInfo& info : allParameters())
        writeParameter(parameters, info, project.parameters.get(info.id));
    root["parameters"] = std::move(parameters);

    ordered_json regions = ordered_json::array();
    for (const GrowthRegion& region : project.regions) {
        ordered_json r;
        r["id"] = region.id;
        r["name"] = region.name;
        r["visible"] = region.visible;
        r["weights"] = encodeFloat32Array(region.weights);
        ordered_json wisp = ordered_json::object();
        for (const ParameterInfo& info : allParameters())
            if (info.group == ParamGroup::Wisp)
                writeParameter(wisp, info, region.values.get(info.id));
        r["wisp"] = std::move(wisp);
        r["root_colour"] = vec3ToJson(region.rootColour);
        r["tip_colour"] = vec3ToJson(region.tipColour);
        if (region.importedStrands) {
            const HairCurves& c = *region.importedStrands;
            std::vector<float> xyz;
            xyz.reserve(c.positions.size() * 3);
            for (const glm::vec3& p : c.positions)
                xyz.insert(xyz.end(), { p.x, p.y, p.z });
            ordered_json strands;
            strands["offsets"] = encodeUint32Array(c.offsets);
            strands["positions"] = encodeFloat32Array(xyz);
            r["imported_strands"] = std::move(strands);
        }
        regions.push_back(std::move(r));
    }
    root["regions"] = std::move(regions);
    root["solo_region"] = project.soloRegion == kNoSolo ? ordered_json(nullptr) : ordered_json(project.soloRegion);

    ordered_json camera;
    camera["pivot"] = vec3ToJson(project.camera.pivot);
    camera["yaw_radians"] = shortestDoubleForFloat(project.camera.yawRadians);
    camera["pitch_radians"] = shortestDoubleForFloat(project.camera.pitchRadians);
    camera["distance_metres"] = shortestDoubleForFloat(project.camera.distanceMetres);
    camera["fov_y_degrees"] = shortestDoubleForFloat(project.camera.fovYDegrees);
    root["camera"] = std::move(camera);
    root["display_density"] = shortestDoubleForFloat(project.displayDensity);

    // Only what the artist changed: default entries, and default fields of an entry, are left out.
    // Compared by bits, so that -0 travels as -0.
    const StrandStyle unchanged;
    const auto differs
        = [](float a, float b) { return std::bit_cast<std::uint32_t>(a) != std::bit_cast<std::uint32_t>(b); };
    ordered_json style = ordered_json::array();
    for (const auto& [identity, edit] : project.style) {
        if (edit.isDefault())
            continue;
        ordered_json entry;
        entry["strand"] = std::to_string(identity);
        if (differs(edit.lengthMetres, unchanged.lengthMetres))
            entry["length"] = shortestDoubleForFloat(edit.lengthMetres);
        if (differs(edit.curlRadiusMetres, unchanged.curlRadiusMetres))
            entry["curl_radius"] = shortestDoubleForFloat(edit.curlRadiusMetres);
        if (differs(edit.curlTurnsPerMetre, unchanged.curlTurnsPerMetre))
            entry["curl_turns"] = shortestDoubleForFloat(edit.curlTurnsPerMetre);
        if (differs(edit.stiffnessScale, unchanged.stiffnessScale))
            entry["stiffness_scale"] = shortestDoubleForFloat(edit.stiffnessScale);
        if (differs(edit.wetness, unchanged.wetness))
            entry["wetness"] = shortestDoubleForFloat(edit.wetness);
        if (!edit.shape.empty()) {
            std::vector<float> xyz;
            xyz.reserve(edit.shape.size() * 3);
            for (const glm::vec3& p : edit.shape)
                xyz.insert(xyz.end(), { p.x, p.y, p.z });
            entry["shape"] = encodeFloat32Array(xyz);
        }
        style.push_back(std::move(entry));
    }
    if (!style.empty())
        root["style"] = std::move(style);
    if (!(project.motion == HeadMotion{}))
        root["motion"] = motionToJson(project.motion);
    if (!(project.timeline == BakeRange{}))
        root["timeline"] = timelineToJson(project.timeline);
    return dumpPretty(root);
}

Result<void> writeProject(const std::string& path, const Project& project, Backup backup)
{
    try {
        checkProject(project);
    } catch (const Refusal& refusal) {
        return IoError{ path, refusal.location, "not saved: " + refusal.message };
    }
    const std::string text = projectToJson(project, path);
    std::error_code error;
    if (fs::is_directory(path, error))
        return IoError{ path, "", "this is a folder; a project is saved as a file" };
    // The backup sits beside the file a symbolic link at `path` leads to, as the new content does.
    if (backup == Backup::Keep && fs::exists(path, error)) {
        const std::string target = writeTargetOf(path);
        if (const Result<void> kept = keepCopyAtomically(target, target + ".bak"); !kept)
            return IoError{ path, "",
                "cannot keep the previous file as .bak (" + kept.error().toString() + "); nothing was saved" };
    }
    return writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

} // namespace wisp::io
