#pragma once
// The head's motion and the timeline in JSON (projects, io/ProjectFile.h):
//
//   "motion": { "keys": [ { "time": 0.5, "translation": [0, 0.01, 0], "rotation": [1, 0, 0, 0] } ],
//               "procedural": { "kind": "shake", "amplitude": 30, "frequency": 1.75, "start": 0 } },
//   "timeline": { "first_frame": 1, "last_frame": 48, "fps": 24 }
//
// Seconds, metres, degrees (metres for walk), Hz; rotations are unit quaternions w, x, y, z. Keys
// in increasing time. Reading checks everything as HeadMotion::validate and validateBakeRange do
// (each number against the registry's range for it, sim/params/Parameters.h's MotionSetting), and
// refuses with the key path of the field ("motion.procedural.amplitude: 120 is outside 0..90 degrees"). Missing objects
// or keys read as the defaults (no motion; frames 1..48 at 24 fps), so older files still open.
//
// Thread safety: any thread; no state.

#include "io/PresetFile.h"
#include "sim/motion/HairBake.h"
#include "sim/motion/HeadMotion.h"

#include <nlohmann/json.hpp>

namespace wisp::io::detail {

nlohmann::ordered_json motionToJson(const HeadMotion& motion);
nlohmann::ordered_json timelineToJson(const BakeRange& timeline);
// Throw Refusal.
HeadMotion readMotion(const nlohmann::json& value, const std::string& path, Warnings& warnings);
BakeRange readTimeline(const nlohmann::json& value, const std::string& path, Warnings& warnings);

} // namespace wisp::io::detail
