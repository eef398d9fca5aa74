#pragma once
// Projects: everything needed to reopen the work exactly: the head (stored in the project, or a
// reference to the mesh file it was imported from), every parameter, the growth regions with
// their painted weights, wisp parameters and colours, the solo'd region and the camera.
//
// Format: JSON, "format": "wisp-project", "version": 1:
//
//   { "format": "wisp-project", "version": 1,
//     "head": { "source": "heads/planck.obj",              // relative to the project's folder
//               "absolute_source": "/home/ana/heads/planck.obj",  // where it was when saved
//               "embedded": true, "import_scale": 0.01, "import_offset": [0, -1.62, 0.01],
//               "import_z_up": false, "vertex_count": 642, "triangle_count": 1280,
//               "positions": "<base64>", "triangles": "<base64>" },   // only when embedded
//     "parameters": { "density": 8.0, ..., "simulate_all_strands": false },   // every registry key
//     "regions": [ { "id": 0, "name": "Scalp", "visible": true, "weights": "<base64>",
//                    "wisp": { "density": 8.0, ... }, "root_colour": [0.16, 0.1, 0.06],
//                    "tip_colour": [0.45, 0.3, 0.17] } ],
//     "solo_region": null,                                   // or a region's id
//     "camera": { "pivot": [0, 1.6, 0], "yaw_radians": 0.5, "pitch_radians": -0.2,
//                 "distance_metres": 0.8, "fov_y_degrees": 35 },
//     "style": [ { "strand": "4294967298", "length": 0.2, "curl_radius": 0.01, "curl_turns": 6,
//                  "stiffness_scale": 3, "wetness": 0.5, "shape": "<base64>" } ] }
//
// "motion" and "timeline" (io/MotionJson.h) hold the head's motion and the timeline's range.
//
// "style" holds the artist's salon edits (sim/style/StyleEdits.h), one entry per edited strand in
// identity order; it is left out when there are none, and a missing "style" means no edits (older
// projects). "strand" is the strand identity (Groom::strandIdentity) as a decimal string, since a
// 64-bit identity does not fit a JSON number exactly. An entry holds only the fields that differ
// from StrandStyle's defaults (a missing field reads as the default): "length" (metres; 0 = the
// region's), "curl_radius" (metres) and "curl_turns" (per metre; negative = the region's),
// "stiffness_scale" (1..50), "wetness" (0..1) and "shape" (the rest shape under gravity, head space,
// metres, root first: base64 float32 x y z per point, at least 2 points). Each entry must pass
// validateStrandStyle; an identity given twice is refused. Entries with nothing changed are not
// written, and are dropped when read.
//
// Binary arrays are base64 (io/Base64.h) of little-endian float32 (positions x y z per vertex,
// one weight per vertex) or uint32 (three vertex indices per triangle). Floats are written as the
// shortest decimal that reads back as the same float, doubles as the shortest that reads back as
// the same double, so a write followed by a read gives bit-identical numbers.
//
// Reading validates everything and refuses with the key path, as presets do ("regions[0].weights:
// 641 weights for a head of 642 vertices", "style[3]: strand 4294967298: wetness 3 is outside 0..1"); unknown keys are
// ignored with a warning. A region's `values` holds only its Wisp-group parameters (GrowthRegion.h): the others read as
// defaults. Writing refuses a project that reading would refuse, so every saved file opens again.
//
// Thread safety: any thread; no state. The head loader is called on the calling thread.

#include "io/HeadOrientation.h"
#include "io/IoError.h"
#include "sim/geometry/TriangleMesh.h"
#include "sim/groom/GrowthRegion.h"
#include "sim/motion/HairBake.h"
#include "sim/motion/HeadMotion.h"
#include "sim/params/Parameters.h"
#include "sim/style/StyleEdits.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace wisp::io {

constexpr int kProjectVersion = 1;
constexpr std::size_t kMaxProjectBytes = std::size_t(1) << 30;

// The orbit camera: it looks at `pivot` from `distanceMetres` away, turned by yaw about +Y and
// pitched above (positive) or below the horizontal.
struct CameraState {
    glm::vec3 pivot{ 0.0f }; // metres
    float yawRadians = 0.0f;
    float pitchRadians = 0.0f;
    float distanceMetres = 1.0f; // > 0
    float fovYDegrees = 35.0f; // vertical field of view, 0..180 exclusive

    bool operator==(const CameraState&) const = default;
};

inline constexpr float kMinDisplayDensity = 0.25f;
inline constexpr float kMaxDisplayDensity = 4.0f;

struct Project {
    TriangleMesh head; // metres, as groomed: the source file's coordinates times headImportScale
    // The file the head came from: "" for the built-in head. In memory an absolute path (readProject
    // returns one); a relative path is taken as relative to the project file's folder. The file
    // stores it relative to the project's folder, and the absolute path as a fallback.
    std::string headSource;
    bool headEmbedded = true; // the head's vertices and triangles are stored in the project; when
                              // false, readProject loads headSource again (it must not be "")
    // How the import placed the file's vertices (io/HeadPlacement.h's HeadPlacement): a vertex p of
    // the file is at orient(p, headImportUp, headImportFront) * headImportScale + headImportOffset
    // in `head` (io/HeadOrientation.h). readProject redoes it for a referenced head; for an
    // embedded head it is only kept, so that a re-import can offer it. Files written before the
    // up axis was found from the shape hold "import_z_up" instead: true reads as +Z up, front -Y.
    float headImportScale = 1.0f; // metres per file unit (0.01 for centimetres)
    glm::vec3 headImportOffset{ 0.0f }; // metres, added after turning and scaling
    io::Axis headImportUp = io::Axis::PosY; // the file's axis that became +Y
    io::Axis headImportFront = io::Axis::PosZ; // the file's axis that became +Z
    ParameterValues parameters; // all of them, written with every registry key
    std::vector<GrowthRegion> regions;
    std::uint32_t soloRegion = kNoSolo; // a region's id, or kNoSolo
    CameraState camera;
    // How many strands the viewport draws per simulated/groomed strand (render-time children,
    // widgets/HairChildren.h): kMinDisplayDensity..kMaxDisplayDensity. Older files: 1.
    float displayDensity = 1.0f;
    // The salon edits (cut, comb, perm, hairspray, wet brush) per strand identity; entries must pass
    // validateStrandStyle. Default entries (isDefault) are not saved.
    StyleEdits style;
    // The head's keyframes and procedural motion, and the timeline's frame range and fps
    // (io/MotionJson.h: "motion" and "timeline", written only when not the defaults; older files
    // read as no motion, frames 1..48 at 24 fps).
    HeadMotion motion;
    BakeRange timeline;
};

struct ProjectReadResult {
    Project project;
    std::vector<std::string> warnings; // unknown keys; a referenced head found only at its old absolute path
};

// Loads a head mesh file for a project whose head is not embedded. Given the absolute path; returns
// the file's coordinates as stored (readProject then places them as the import did).
using HeadLoader = std::function<Result<TriangleMesh>(const std::string& absolutePath)>;
// The HeadLoader every tool uses: the mesh file read by io::readMesh (any format it reads).
Result<TriangleMesh> readHeadFile(const std::string& absolutePath);

// `loadHead` is needed only for projects whose head is not embedded. A missing referenced head is
// an error naming the project and the head paths tried: the relative "source" resolved against the
// project's folder first, then "absolute_source" (with a warning when that one is used).
Result<ProjectReadResult> readProject(const std::string& path, const HeadLoader& loadHead = {});
// The same for a project's text already in memory (an autosave, a test): `projectPath` names it in
// errors and is where a relative head source is resolved from.
Result<ProjectReadResult> parseProject(
    std::string_view json, const std::string& projectPath, const HeadLoader& loadHead = {});

// Atomic (io/AtomicFile.h); an existing file at `path` is first kept as path + ".bak" (replacing an
// older .bak; where `path` is a symbolic link, beside the file it leads to, which gets the new
// content while the link stays). On failure nothing at `path` has changed and no temporary file is
// left; a process killed while saving leaves the old or the new file and a temporary that
// removeStaleTemporaryFiles takes away.
// `backup` false writes no .bak (autosaves: the atomic write is enough, and a .bak would outlive them).
enum class Backup { Keep, None };
Result<void> writeProject(const std::string& path, const Project& project, Backup backup = Backup::Keep);

// The text writeProject writes; `projectPath` decides the relative head source.
std::string projectToJson(const Project& project, const std::string& projectPath);

} // namespace wisp::io
