#pragma once
// Presets: a named look that applies to any head. A preset holds every global parameter (the
// registry's Groom, Forces and Solver groups) and, per growth region, its wisp parameters and its
// colours; it never holds a head or painted weights. The format is versioned JSON, documented for
// users in resources/presets/README.md:
//
//   { "format": "wisp-preset", "version": 2, "name": "Wavy", "description": "Loose waves",
//     "parameters": { "gravity": 9.81, "segments": 20, ... },           // global keys only
//     "regions": [ { "name": "Scalp",
//                    "wisp": { "length": 0.35, "curl_radius": 0.01, ... },   // Wisp-group keys only
//                    "root_colour": [0.16, 0.1, 0.06], "tip_colour": [0.45, 0.3, 0.17] } ] }
//
// Reading:
//   - A missing key takes the registry's default (a missing colour the GrowthRegion default); a
//     missing "regions" means a preset that changes only the global parameters.
//   - A region may also hold its wisp keys directly ({"name": "Fringe", "length": 0.1}), as people
//     write by hand; "wisp" is what Wisp writes. A key given both ways is refused.
//   - Version 1 (older, still read) has one flat "parameters" object with every key, wisp keys
//     included; its wisp keys become one region named "Scalp".
//   - A version newer than kPresetVersion is refused ("version 3 is newer than this Wisp reads (2)").
//   - Unknown keys, and keys in the wrong place (a global key inside a region), are ignored with a
//     warning naming their path ("regions[0].wisp.sheen: unknown key, ignored").
//   - A wrong type or a value outside the registry's range is refused with its path and the value
//     as written: "regions[1].clump_degree: 3.0 is outside -1..1", "parameters.gravity: \"strong\"
//     is not a number", "regions[0].root_colour: expected 3 numbers 0..1"; integer parameters must
//     be whole numbers. JSON syntax errors give "line L, column C" (columns count bytes).
//   - Limits, so a hostile file cannot hang the editor: 16 MiB per file, 256 regions, names of
//     256 bytes and descriptions of 64 KiB.
//
// Thread safety: every function here may run on any thread; none keeps state.

#include "io/IoError.h"
#include "io/ReadFailure.h"
#include "sim/motion/HeadMotion.h"
#include "sim/params/Parameters.h"

#include <glm/vec3.hpp>
#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace wisp::io {

constexpr int kPresetVersion = 2;
constexpr std::size_t kMaxPresetBytes = 16u << 20;
constexpr std::size_t kMaxRegions = 256; // presets and projects
constexpr std::size_t kMaxNameBytes = 256; // preset and region names
constexpr std::size_t kMaxDescriptionBytes = 64u << 10;

// A region's look without its painted weights.
struct RegionLook {
    std::string name;
    ParameterValues wisp; // only the Wisp-group entries mean anything; the others stay at defaults
    glm::vec3 rootColour{ 0.16f, 0.10f, 0.06f }; // sRGB 0..1 (GrowthRegion's defaults)
    glm::vec3 tipColour{ 0.45f, 0.30f, 0.17f };

    bool operator==(const RegionLook&) const = default;
};

struct Preset {
    std::string name; // a missing name reads as the file's stem
    std::string description;
    ParameterValues parameters; // only the Groom, Forces and Solver entries; Wisp entries stay at defaults
    std::vector<RegionLook> regions;
    // The head's procedural motion ("motion": { "procedural": … }, as in projects, io/MotionJson.h);
    // kind None: the preset leaves the head's motion alone. Keys are a shot's, not a look's: a
    // preset keeps none.
    ProceduralMotion motion;

    bool operator==(const Preset&) const = default;
};

struct PresetReadResult {
    Preset preset;
    std::vector<std::string> warnings; // "regions[0].wisp.sheen: unknown key, ignored"; never fatal
};

Result<PresetReadResult> readPreset(const std::string& path);
// For presets that are not files (Qt resources): `nameForMessages` is the IoError's file.
Result<PresetReadResult> parsePreset(std::string_view json, const std::string& nameForMessages);
// Version 2, indented, keys in registry order; what writePreset writes.
std::string presetToJson(const Preset& preset);
// Atomic (io/AtomicFile.h): readers see the old file or the new one, never half.
Result<void> writePreset(const std::string& path, const Preset& preset);

// ---- Shared with ProjectFile.cpp; not for callers ------------------------------------------------
namespace detail {

// Thrown inside the readers and turned into an IoError at the public functions: io's one parser
// error (io/ReadFailure.h); its location is a key path such as "regions[1].clump_degree", or
// "line 3, column 7".
using Refusal = ReadFailure;

// Collects warnings, at most a screenful: a file with a million unknown keys gives 50 lines.
class Warnings {
public:
    void add(const std::string& path, const std::string& what);
    std::vector<std::string> take();

private:
    std::vector<std::string> m_lines;
    std::size_t m_unreported = 0;
};

// Parses JSON; syntax errors become a Refusal at "line L, column C". `what` names the kind of
// file in messages ("preset").
nlohmann::json parseJson(std::string_view text, std::size_t maxBytes, const char* what);
// Checks "format" (`format`; a file of `otherFormat` is refused as `otherKind`, "a Wisp project")
// and "version" (1 ..`newestVersion`); returns the version. `kind` names the file in messages.
int checkFormatAndVersion(const nlohmann::json& root, std::string_view format, const char* kind, int newestVersion,
    std::string_view otherFormat, const char* otherKind);

// A value as the file wrote it, for messages: 3.0, "strong" (shortened), an object.
std::string describe(const nlohmann::json& value);
std::string childPath(const std::string& path, std::string_view key); // "regions[0]" + "wisp"
const nlohmann::json& requireObject(const nlohmann::json& value, const std::string& path);
std::string readText(const nlohmann::json& value, const std::string& path, std::size_t maxBytes);
double readFiniteNumber(const nlohmann::json& value, const std::string& path);
bool readBool(const nlohmann::json& value, const std::string& path);
// Checks type, wholeness and range for parameter `info`, then sets it.
void readParameter(
    ParameterValues& into, const ParameterInfo& info, const nlohmann::json& value, const std::string& path);
glm::vec3 readColour(const nlohmann::json& value, const std::string& path);

// The double nearest the shortest decimal that reads back as `value`: JSON shows 0.16 rather than
// 0.1599999964237213, and converting the double back to float gives `value` bit for bit.
double shortestDoubleForFloat(float value);
void writeParameter(nlohmann::ordered_json& object, const ParameterInfo& info, double value);
nlohmann::ordered_json vec3ToJson(const glm::vec3& value);
// Indented by 2, with short arrays of numbers ([0.16, 0.1, 0.06]) kept on one line.
std::string dumpPretty(const nlohmann::ordered_json& root);

} // namespace detail

} // namespace wisp::io
