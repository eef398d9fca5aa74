#pragma once
// A scene's hair settled for a still image (`wisp --render`, the presets' thumbnails): groomed and
// draped at rest as the editor's simulation starts a scene, then stepped a fixed number of steps.
// Deterministic: the same scene and step count give the same frame, however busy the machine is
// (a wall-clock settle would not).
//
// fillFrame is the one place a Frame is filled from a HairSimulation (the editor's simulation
// thread uses it too).
//
// Thread: any; settleScene owns its simulation for the call.

#include "sim/geometry/TriangleMesh.h"
#include "sim/groom/GrowthRegion.h"
#include "sim/params/Parameters.h"
#include "sim/solver/Frame.h"
#include "sim/style/StyleEdits.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace wisp {

class HairSimulation;

struct SceneToSettle {
    TriangleMesh head;
    std::vector<GrowthRegion> regions;
    std::uint32_t soloId = kNoSolo;
    ParameterValues values;
    StyleEditsPtr style; // null: no salon edits
};

struct SettledFrame {
    FramePtr frame; // null on error
    std::string error; // what went wrong; empty on success
};

// A drape is done when no particle moves more than this over 10 steps (metres).
inline constexpr float kDrapeStillMetres = 2e-4f;

// Steps of `timeStepSeconds` that simulate `seconds` (rounded; at least 0, at most kMaxSettleSteps).
int settleStepsFor(double seconds, double timeStepSeconds);
inline constexpr int kMaxSettleSteps = 100000;

// Grooms `scene`, drapes it at rest, runs `steps` solver steps and returns the last frame.
// `cancelled` (may be empty) is asked between steps; a cancelled settle returns "cancelled".
SettledFrame settleScene(
    const SceneToSettle& scene, int steps, int solverThreads = 1, const std::function<bool()>& cancelled = {});

// The frame's strands, looks, simulated counts, wind and wetness from `sim` (solver state as it is
// now); step, groom version, times and pacing are the caller's.
void fillFrame(const HairSimulation& sim, const ParameterValues& values, Frame& frame);

} // namespace wisp
