#pragma once
// How finely the hair's curves are sampled on screen: a level of detail along the strands chosen by
// how far a chord would stray from the curve, not by how long it is.
//
// A Catmull-Rom segment L pixels long that turns θ radians, drawn as n chords, strays from the curve
// by about one chord's sagitta, (L / n)(θ / n) / 8 = Lθ / (8n²) pixels (a circular arc's sagitta,
// s = cφ / 8 for chord c and small turn φ). HairRenderer draws the fewest samples a segment (1, 2
// or 4) that keep this under half a pixel for the hair's typical turn: at the editor's default
// framing (segments ~26 px, hair hanging almost straight) one sample a segment, the points
// themselves; curled hair or a close-up gets more. A software rasteriser spends most of the hair's
// time per vertex and per line segment, so every sample saved counts (README, "The hair's look").
//
// Pure C++ (no GL): tested without a context. Thread: any.

#include "sim/geometry/HairCurves.h"

#include <cstddef>

namespace wisp {

// How much the strands turn at a joint, radians: the 90th percentile over the joints of an even
// sample of at most `maxStrands` strands (non-finite or zero-length segments are skipped); 0 for
// straight hair or none.
float typicalTurnRadians(const HairCurves& strands, std::size_t maxStrands = 256);

// The index into HairStripLayout::kSampleSteps (0: four samples a segment, 1: two, 2: one) that
// keeps chords within `maxDeviationPixels` of the curve for segments `segmentPixels` long turning
// `turnRadians` at each joint.
std::size_t sampleStepIndex(float segmentPixels, float turnRadians, float maxDeviationPixels);

} // namespace wisp
