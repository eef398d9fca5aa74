// Reading a project (.wisp): the JSON checked field by field, the head embedded or referenced.
#include "io/HeadPlacement.h"
#include "io/JsonErrors.h"
#include "io/MeshReader.h"
#include "io/MotionJson.h"
#include "io/ProjectFile.h"
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
using namespace project_detail;

namespace {

// ---- reading ----------------------------------------------------------------------------------

float readFloat(const json& value, const std::string& path)
{
    const float number = static_cast<float>(readFiniteNumber(value, path));
    if (!std::isfinite(number))
        throw Refusal{ path, describe(value) + " is too large" };
    return number;
}

// A whole number 0..maximum (counts, ids).
std::uint64_t readWhole(const json& value, const std::string& path, std::uint64_t maximum)
{
    const double number = readFiniteNumber(value, path);
    if (std::floor(number) != number || number < 0.0 || number > static_cast<double>(maximum))
        throw Refusal{ path, describe(value) + " is not a whole number 0.." + std::to_string(maximum) };
    return static_cast<std::uint64_t>(number);
}

const json* find(const json& object, const char* key)
{
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

const json& require(const json& object, const std::string& objectPath, const char* key)
{
    if (const json* value = find(object, key))
        return *value;
    throw Refusal{ childPath(objectPath, key), "missing" };
}

void warnUnknownKeys(
    const json& object, const std::string& path, const std::set<std::string>& known, Warnings& warnings)
{
    for (const auto& [key, value] : object.items())
        if (!known.contains(key))
            warnings.add(childPath(path, key), "unknown key, ignored");
}

std::vector<float> readFloatArray(const json& value, const std::string& path)
{
    if (!value.is_string())
        throw Refusal{ path, describe(value) + " is not base64 text" };
    std::optional<std::vector<float>> values = decodeFloat32Array(value.get_ref<const std::string&>());
    if (!values)
        throw Refusal{ path, "not valid base64 of little-endian 32-bit floats" };
    return std::move(*values);
}

std::vector<std::uint32_t> readUint32Array(const json& value, const std::string& path)
{
    if (!value.is_string())
        throw Refusal{ path, describe(value) + " is not base64 text" };
    std::optional<std::vector<std::uint32_t>> values = decodeUint32Array(value.get_ref<const std::string&>());
    if (!values)
        throw Refusal{ path, "not valid base64 of little-endian 32-bit unsigned integers" };
    return std::move(*values);
}

glm::vec3 readFiniteVec3(const json& value, const std::string& path)
{
    const bool ok = value.is_array() && value.size() == 3 && std::all_of(value.begin(), value.end(), [](const json& c) {
        return c.is_number() && std::isfinite(static_cast<float>(c.get<double>()));
    });
    if (!ok)
        throw Refusal{ path, "expected 3 finite numbers" };
    return { static_cast<float>(value[0].get<double>()), static_cast<float>(value[1].get<double>()),
        static_cast<float>(value[2].get<double>()) };
}

void readEmbeddedHead(const json& head, std::uint64_t vertexCount, std::uint64_t triangleCount, TriangleMesh& mesh)
{
    const std::vector<float> positions = readFloatArray(require(head, "head", "positions"), "head.positions");
    if (positions.size() != 3 * vertexCount)
        throw Refusal{ "head.positions",
            std::to_string(positions.size()) + " numbers where the " + std::to_string(vertexCount) + " vertices need "
                + std::to_string(3 * vertexCount) };
    const std::vector<std::uint32_t> indices = readUint32Array(require(head, "head", "triangles"), "head.triangles");
    if (indices.size() != 3 * triangleCount)
        throw Refusal{ "head.triangles",
            std::to_string(indices.size()) + " indices where the " + std::to_string(triangleCount) + " triangles need "
                + std::to_string(3 * triangleCount) };
    mesh.positions.resize(vertexCount);
    for (std::size_t v = 0; v < vertexCount; ++v)
        mesh.positions[v] = { positions[3 * v], positions[3 * v + 1], positions[3 * v + 2] };
    mesh.triangles.resize(triangleCount);
    for (std::size_t t = 0; t < triangleCount; ++t)
        mesh.triangles[t] = { indices[3 * t], indices[3 * t + 1], indices[3 * t + 2] };
}

void readReferencedHead(const std::string& projectPath, const fs::path& folder, const std::string& source,
    const std::string& absoluteSource, std::uint64_t vertexCount, const HeadLoader& loadHead, Project& project,
    Warnings& warnings)
{
    const fs::path primary = resolveAgainst(folder, source);
    fs::path chosen = primary;
    std::error_code error;
    if (!fs::exists(primary, error)) {
        const bool fallback = !absoluteSource.empty() && fs::path(absoluteSource) != primary;
        if (fallback && fs::exists(absoluteSource, error)) {
            chosen = absoluteSource;
            warnings.add("head.source",
                "\"" + source + "\" is not at " + primary.string() + "; loaded " + absoluteSource
                    + ", where it was when the project was saved");
        } else {
            throw Refusal{ "head.source",
                "cannot find the head file " + primary.string() + " (\"" + source + "\" next to the project "
                    + (folder / fs::path(projectPath).filename()).string() + ")"
                    + (fallback ? " nor at " + absoluteSource : "") };
        }
    }
    if (!loadHead)
        throw Refusal{ "head.source", "the head is in " + chosen.string() + ", and no head loader was given" };
    Result<TriangleMesh> loaded = loadHead(chosen.string());
    if (!loaded)
        throw Refusal{ "head.source", "cannot load the head: " + loaded.error().toString() };
    project.head = std::move(loaded).value();
    // io/HeadPlacement.cpp's applyPlacement, so the head lands where the import put it.
    HeadPlacement placement;
    placement.scale = project.headImportScale;
    placement.offset = project.headImportOffset;
    placement.up = project.headImportUp;
    placement.front = project.headImportFront;
    applyPlacement(project.head, placement);
    if (project.head.vertexCount() != vertexCount)
        throw Refusal{ "head.source",
            chosen.string() + " has " + std::to_string(project.head.vertexCount())
                + " vertices, but the project was painted on " + std::to_string(vertexCount)
                + " (was the file changed?)" };
    project.headSource = chosen.string();
}

void readHead(const json& root, const std::string& projectPath, const fs::path& folder, const HeadLoader& loadHead,
    Project& project, Warnings& warnings)
{
    const json& head = requireObject(require(root, "", "head"), "head");
    warnUnknownKeys(head, "head",
        { "source", "absolute_source", "embedded", "import_scale", "import_offset", "import_z_up", "import_up",
            "import_front", "vertex_count", "triangle_count", "positions", "triangles" },
        warnings);
    std::string source, absoluteSource;
    if (const json* value = find(head, "source"))
        source = readText(*value, "head.source", kMaxPathBytes);
    if (const json* value = find(head, "absolute_source"))
        absoluteSource = readText(*value, "head.absolute_source", kMaxPathBytes);
    if (const json* value = find(head, "embedded"))
        project.headEmbedded = readBool(*value, "head.embedded");
    if (const json* value = find(head, "import_scale"))
        project.headImportScale = readFloat(*value, "head.import_scale");
    if (const json* value = find(head, "import_offset"))
        project.headImportOffset = readFiniteVec3(*value, "head.import_offset");
    if (const json* value = find(head, "import_z_up"); value && readBool(*value, "head.import_z_up")) {
        project.headImportUp = Axis::PosZ;
        project.headImportFront = defaultFront(Axis::PosZ);
    }
    for (auto [key, axis] :
        { std::pair{ "import_up", &project.headImportUp }, std::pair{ "import_front", &project.headImportFront } })
        if (const json* value = find(head, key)) {
            const std::string text = readText(*value, std::string("head.") + key, 8);
            const std::optional<Axis> parsed = parseAxis(text);
            if (!parsed)
                throw Refusal{ std::string("head.") + key, "\"" + text + "\" is no axis (+X, -X, +Y, -Y, +Z or -Z)" };
            *axis = *parsed;
        }
    if (glm::dot(axisVector(project.headImportUp), axisVector(project.headImportFront)) != 0.0f)
        throw Refusal{ "head.import_front",
            std::string(axisName(project.headImportFront)) + " is not perpendicular to " + "head.import_up "
                + axisName(project.headImportUp) };
    const std::uint64_t vertexCount
        = readWhole(require(head, "head", "vertex_count"), "head.vertex_count", 0xffffffffu);
    const std::uint64_t triangleCount
        = readWhole(require(head, "head", "triangle_count"), "head.triangle_count", 0xffffffffu);
    if (project.headEmbedded) {
        readEmbeddedHead(head, vertexCount, triangleCount, project.head);
        project.headSource = source.empty() ? "" : resolveAgainst(folder, source).string();
    } else {
        if (source.empty())
            throw Refusal{ "head.source", "a head that is not stored in the project needs the file it comes from" };
        readReferencedHead(projectPath, folder, source, absoluteSource, vertexCount, loadHead, project, warnings);
    }
}

GrowthRegion readRegion(const json& value, std::size_t index, Warnings& warnings)
{
    const std::string path = regionPath(index);
    requireObject(value, path);
    warnUnknownKeys(value, path,
        { "id", "name", "visible", "weights", "wisp", "root_colour", "tip_colour", "imported_strands" }, warnings);
    GrowthRegion region;
    region.id = static_cast<std::uint32_t>(readWhole(require(value, path, "id"), path + ".id", 0xffffffffu));
    region.name = "Region " + std::to_string(index + 1);
    if (const json* name = find(value, "name"))
        region.name = readText(*name, path + ".name", kMaxNameBytes);
    if (const json* visible = find(value, "visible"))
        region.visible = readBool(*visible, path + ".visible");
    region.weights = readFloatArray(require(value, path, "weights"), path + ".weights");
    if (const json* wisp = find(value, "wisp")) {
        const std::string wispPath = path + ".wisp";
        for (const auto& [key, parameter] : requireObject(*wisp, wispPath).items()) {
            const std::string keyPath = childPath(wispPath, key);
            const ParameterInfo* info = findParameter(key);
            if (!info)
                warnings.add(keyPath, "unknown key, ignored");
            else if (info->group != ParamGroup::Wisp)
                warnings.add(keyPath, "a global parameter, which belongs in \"parameters\"; ignored here");
            else
                readParameter(region.values, *info, parameter, keyPath);
        }
    }
    if (const json* colour = find(value, "root_colour"))
        region.rootColour = readColour(*colour, path + ".root_colour");
    if (const json* colour = find(value, "tip_colour"))
        region.tipColour = readColour(*colour, path + ".tip_colour");
    if (const json* strands = find(value, "imported_strands")) {
        const std::string strandsPath = path + ".imported_strands";
        requireObject(*strands, strandsPath);
        auto curves = std::make_shared<HairCurves>();
        curves->offsets = readUint32Array(require(*strands, strandsPath, "offsets"), strandsPath + ".offsets");
        const std::vector<float> xyz
            = readFloatArray(require(*strands, strandsPath, "positions"), strandsPath + ".positions");
        if (xyz.size() % 3 != 0)
            throw Refusal{ strandsPath + ".positions", std::to_string(xyz.size()) + " numbers are not whole points" };
        curves->positions.resize(xyz.size() / 3);
        for (std::size_t i = 0; i < curves->positions.size(); ++i) {
            curves->positions[i] = { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
            if (!std::isfinite(xyz[3 * i] + xyz[3 * i + 1] + xyz[3 * i + 2]))
                throw Refusal{ strandsPath + ".positions", "point " + std::to_string(i) + " is not finite" };
        }
        if (curves->offsets.empty() || curves->offsets.front() != 0
            || curves->offsets.back() != curves->positions.size()
            || !std::is_sorted(curves->offsets.begin(), curves->offsets.end()))
            throw Refusal{ strandsPath + ".offsets",
                "do not describe the " + std::to_string(curves->positions.size())
                    + " points (they must rise from 0 to the point count)" };
        region.importedStrands = std::move(curves);
    }
    return region;
}

std::uint64_t readStrandIdentity(const json& value, const std::string& path)
{
    if (!value.is_string())
        throw Refusal{ path,
            describe(value) + " is not a strand identity (a decimal number in double quotes, such as \"4294967298\")" };
    const std::string& text = value.get_ref<const std::string&>();
    std::uint64_t identity = 0;
    const char* end = text.data() + text.size();
    const bool digitsOnly
        = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
    const auto [stop, error] = std::from_chars(text.data(), end, identity);
    if (digitsOnly && error == std::errc::result_out_of_range)
        throw Refusal{ path, describe(value) + " is too large for a strand identity (at most 18446744073709551615)" };
    if (!digitsOnly || error != std::errc() || stop != end)
        throw Refusal{ path, describe(value) + " is not a strand identity (a decimal number)" };
    return identity;
}

// One entry of "style"; a missing field keeps StrandStyle's default.
std::pair<std::uint64_t, StrandStyle> readStyleEntry(const json& value, const std::string& path, Warnings& warnings)
{
    requireObject(value, path);
    warnUnknownKeys(value, path,
        { "strand", "length", "curl_radius", "curl_turns", "stiffness_scale", "wetness", "shape" }, warnings);
    const std::uint64_t identity = readStrandIdentity(require(value, path, "strand"), path + ".strand");
    StrandStyle style;
    if (const json* length = find(value, "length"))
        style.lengthMetres = readFloat(*length, path + ".length");
    if (const json* radius = find(value, "curl_radius"))
        style.curlRadiusMetres = readFloat(*radius, path + ".curl_radius");
    if (const json* turns = find(value, "curl_turns"))
        style.curlTurnsPerMetre = readFloat(*turns, path + ".curl_turns");
    if (const json* stiffness = find(value, "stiffness_scale"))
        style.stiffnessScale = readFloat(*stiffness, path + ".stiffness_scale");
    if (const json* wetness = find(value, "wetness"))
        style.wetness = readFloat(*wetness, path + ".wetness");
    if (const json* shape = find(value, "shape")) {
        const std::string shapePath = path + ".shape";
        const std::vector<float> xyz = readFloatArray(*shape, shapePath);
        if (xyz.size() % 3 != 0)
            throw Refusal{ shapePath, std::to_string(xyz.size()) + " numbers are not whole points" };
        style.shape.resize(xyz.size() / 3);
        for (std::size_t i = 0; i < style.shape.size(); ++i) {
            style.shape[i] = { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
            if (!std::isfinite(xyz[3 * i]) || !std::isfinite(xyz[3 * i + 1]) || !std::isfinite(xyz[3 * i + 2]))
                throw Refusal{ shapePath, "point " + std::to_string(i) + " is not finite" };
        }
    }
    if (std::string error = validateStrandStyle(identity, style); !error.empty())
        throw Refusal{ path, error };
    return { identity, std::move(style) };
}

void readStyle(const json& value, StyleEdits& edits, Warnings& warnings)
{
    if (!value.is_array())
        throw Refusal{ "style", "expected a list [ ... ] of strand edits, found " + describe(value) };
    std::map<std::uint64_t, std::size_t> indexOfIdentity;
    for (std::size_t i = 0; i < value.size(); ++i) {
        const std::string path = stylePath(i);
        auto [identity, style] = readStyleEntry(value[i], path, warnings);
        if (const auto [it, added] = indexOfIdentity.emplace(identity, i); !added)
            throw Refusal{ path + ".strand",
                std::to_string(identity) + " is already the strand of " + stylePath(it->second) };
        if (!style.isDefault()) // nothing changed: not an edit
            edits.emplace(identity, std::move(style));
    }
}

void readCamera(const json& value, CameraState& camera, Warnings& warnings)
{
    requireObject(value, "camera");
    warnUnknownKeys(
        value, "camera", { "pivot", "yaw_radians", "pitch_radians", "distance_metres", "fov_y_degrees" }, warnings);
    if (const json* pivot = find(value, "pivot"))
        camera.pivot = readFiniteVec3(*pivot, "camera.pivot");
    if (const json* yaw = find(value, "yaw_radians"))
        camera.yawRadians = readFloat(*yaw, "camera.yaw_radians");
    if (const json* pitch = find(value, "pitch_radians"))
        camera.pitchRadians = readFloat(*pitch, "camera.pitch_radians");
    if (const json* distance = find(value, "distance_metres"))
        camera.distanceMetres = readFloat(*distance, "camera.distance_metres");
    if (const json* fov = find(value, "fov_y_degrees"))
        camera.fovYDegrees = readFloat(*fov, "camera.fov_y_degrees");
}

Project readProjectJson(
    const json& root, const std::string& projectPath, const HeadLoader& loadHead, Warnings& warnings)
{
    checkFormatAndVersion(root, "wisp-project", "project", kProjectVersion, "wisp-preset", "a Wisp preset");
    warnUnknownKeys(root, "",
        { "format", "version", "head", "parameters", "regions", "solo_region", "camera", "display_density", "style",
            "motion", "timeline" },
        warnings);
    Project project;
    readHead(root, projectPath, projectFolder(projectPath), loadHead, project, warnings);
    if (const json* parameters = find(root, "parameters")) {
        for (const auto& [key, value] : requireObject(*parameters, "parameters").items()) {
            const std::string path = childPath("parameters", key);
            if (const ParameterInfo* info = findParameter(key))
                readParameter(project.parameters, *info, value, path);
            else
                warnings.add(path, "unknown key, ignored");
        }
    }
    if (const json* regions = find(root, "regions")) {
        if (!regions->is_array())
            throw Refusal{ "regions", "expected a list [ ... ] of regions, found " + describe(*regions) };
        if (regions->size() > kMaxRegions)
            throw Refusal{ "regions",
                std::to_string(regions->size()) + " regions; at most " + std::to_string(kMaxRegions) + " are allowed" };
        for (std::size_t i = 0; i < regions->size(); ++i)
            project.regions.push_back(readRegion((*regions)[i], i, warnings));
    }
    if (const json* solo = find(root, "solo_region"); solo && !solo->is_null())
        project.soloRegion = static_cast<std::uint32_t>(readWhole(*solo, "solo_region", 0xffffffffu));
    if (const json* camera = find(root, "camera"))
        readCamera(*camera, project.camera, warnings);
    if (const json* density = find(root, "display_density"))
        project.displayDensity = readFloat(*density, "display_density");
    if (const json* style = find(root, "style"))
        readStyle(*style, project.style, warnings);
    if (const json* motion = find(root, "motion"))
        project.motion = readMotion(*motion, "motion", warnings);
    if (const json* timeline = find(root, "timeline"))
        project.timeline = readTimeline(*timeline, "timeline", warnings);
    checkProject(project);
    return project;
}

} // namespace

Result<TriangleMesh> readHeadFile(const std::string& absolutePath)
{
    Result<MeshReadResult> mesh = readMesh(absolutePath);
    if (!mesh)
        return mesh.error();
    return std::move(mesh).value().mesh;
}

Result<ProjectReadResult> readProject(const std::string& path, const HeadLoader& loadHead)
{
    std::string text;
    try {
        text = readRegularFileOrFail(path, { kMaxProjectBytes, "project", true });
    } catch (const Refusal& refusal) {
        return IoError{ path, refusal.location, refusal.message };
    } catch (const std::bad_alloc&) {
        return IoError{ path, "", "not enough memory to read the project" };
    }
    return parseProject(text, path, loadHead);
}

Result<ProjectReadResult> parseProject(std::string_view text, const std::string& path, const HeadLoader& loadHead)
{
    try {
        const json root = parseJson(text, kMaxProjectBytes, "project");
        Warnings warnings;
        Project project = readProjectJson(root, path, loadHead, warnings);
        // The same check as Open Head and wisp-cli: a flat or absurdly large head is refused
        // before the editor builds its BVH, collider and groom on it.
        if (std::string problem = checkPlacedHead(project.head); !problem.empty())
            throw Refusal{ "head", problem };
        return ProjectReadResult{ std::move(project), warnings.take() };
    } catch (const Refusal& refusal) {
        return IoError{ path, refusal.location, refusal.message };
    } catch (const json::exception& e) { // a check above missed a case: still an error, not a crash
        return IoError{ path, "", withoutJsonPrefix(e.what()) };
    } catch (const std::bad_alloc&) {
        return IoError{ path, "", "not enough memory to read the project" };
    }
}

} // namespace wisp::io
