#pragma once
// What every salon brush reads (after Blender's curves_sculpt_* operations and their executors):
// the context a stroke runs in (the hair as drawn, the head, the brush's settings) and one sample
// of the stroke (a view ray from the artist's eye, as the cursor gives it in the editor and a
// stroke point gives it in wisp-cli). Frames are world space; the head (picking, its mirror plane)
// and brush edits (StyleEdits) are head space; the frame's headToWorld joins them (the head moves
// with its motion, HeadMotion.h). Names say which space they mean (_ws world, _hs head).

#include "sim/geometry/HeadModel.h"
#include "sim/groom/ScalpBrush.h"
#include "sim/solver/Frame.h"
#include "sim/solver/FrameSpace.h"
#include "sim/style/HairDryer.h"
#include "sim/style/StyleEdits.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace wisp {

class HairSimulation;

// The salon brushes (Lee et al.'s cut, comb and perm; Ward et al.'s wet hair, hairspray, blow-dryer).
enum class StyleBrush { Comb, Cut, Length, Curl, Wet, Hairspray, BlowDry };

struct BrushContext {
    FramePtr frame; // the newest frame; its groomShape names its strands (the caller refreshes it)
    HeadModelPtr head; // picking, the mirror plane, the cut's line of sight; may be null (no head)
    BrushSettings brush; // radius, strength, falloff, X mirror (mode is the growth brush's only)
    bool everyStrandSimulated = false; // Param::SimulateAllStrands: else only key hairs are simulated
    float curlRadiusMetres = 0.01f; // the perm's curl
    float curlTurnsPerMetre = 10.0f;
};

// One point of a stroke: the view ray through it.
struct BrushSample {
    glm::vec3 eye_ws{ 0.0f }; // where the ray starts, metres
    glm::vec3 direction_ws{ 0.0f, 0.0f, -1.0f }; // unit
    float aimDepthMetres = 1.0f; // along the ray: where the dryer aims when the ray misses the head
    bool inverted = false; // Ctrl: shrink, take the perm out, towel-dry, wash the spray out
};

// A ray a brush picks strands along, and how deep it reaches (the head's surface under it plus the
// brush radius: hair behind the head is not touched).
struct BrushRay {
    glm::vec3 origin_ws{ 0.0f };
    glm::vec3 direction_ws{ 0.0f, 0.0f, -1.0f };
    float maxDepthMetres = 1.0e4f;
};

// The sample's ray and, with X mirror on, its mirror across the head's mirror plane (second; the
// plane is the head's, so it turns and moves with it).
std::vector<BrushRay> brushRays(const BrushContext& context, const BrushSample& sample);

// Head space to world space in the context's frame, and back: headToWorldOf(context.frame),
// worldToHeadOf(context.frame) (sim/solver/FrameSpace.h).
// Where a world ray meets the head, world space (the head is picked in its own space); nullopt
// when it misses or there is no head.
std::optional<HeadModel::SurfaceHit> headHitAlong(
    const BrushContext& context, const glm::vec3& origin_ws, const glm::vec3& direction_ws);

// True when the context's frame names its strands (a frame from before the first groom does not).
bool hasStyledHair(const BrushContext& context);

// The strand's length now (metres): what `edits` set for it, else its groomed length.
float strandLengthNow(
    const BrushContext& context, const StyleEdits& edits, std::uint64_t identity, std::uint32_t strand);

// The strand a brush holds for `strand`: itself when every strand is simulated (or it has no wisp),
// else its wisp's key hair (members follow their key).
std::uint32_t heldStrandOf(const BrushContext& context, std::uint32_t strand);

// The dryer's nozzle is this far in front of the hair it points at.
constexpr float kDryerDistanceMetres = 0.12f;
// The dryer held at a sample: aimed along the ray at the head's surface under it (or, past the
// head, at aimDepthMetres), its nozzle kDryerDistanceMetres in front of that point; with X mirror,
// a second dryer mirrored.
std::vector<HairDryer> dryersFor(const BrushContext& context, const BrushSample& sample);

// The shape of a simulation's groom, as frames carry it (Frame.h): rest pose, key strands,
// identities, wisps, lengths. Thread: the simulation's.
std::shared_ptr<const GroomShape> groomShapeOf(const HairSimulation& simulation);

} // namespace wisp
