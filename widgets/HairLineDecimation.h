#pragma once
// Fewer line segments where a strand is straight enough on screen: the hair's lines at one sample a
// segment (the points themselves) leave out a point wherever the chord that skips it passes within a
// tolerance of it, so a straight run of hair is drawn with half the segments and a bend keeps its
// points. The same rule as the samples a segment (HairSampling.h): no chord strays from the curve by
// more than the style's maxDeviationPixels. On Mesa's llvmpipe the hair pass is the lines' setup and
// rasterisation, per segment (README, "The hair's look"), so every segment left out counts.
//
// At most every other point goes (a chord spans at most two segments), so the along-strand shading,
// interpolated between the kept points, stays what it was to within one segment.
//
// Pure C++ (no GL): tested without a context. Thread: any.

#include "sim/geometry/HairCurves.h"
#include "widgets/HairStripLayout.h"

#include <span>
#include <vector>

namespace wisp {

// Per point, metres: how far it lies from the chord between its two neighbours along the strand;
// +infinity at a strand's ends and wherever a neighbour or the point is not finite (never left out).
std::vector<float> chordDeviations(const HairCurves& strands);

// The line strips of `layout` at one sample a segment (its lines[kOneSampleStep]), leaving out each
// point whose deviation is at most `toleranceMetres` and whose predecessor was kept; the prefix
// still counts whole strands in drawing order. `deviations` is chordDeviations of the strands the
// layout was built for (any other size: nothing is left out).
HairStripLayout::IndexList decimatedLines(
    const HairStripLayout& layout, std::span<const float> deviations, float toleranceMetres);

// The index of one sample a segment in HairStripLayout::kSampleSteps.
inline constexpr std::size_t kOneSampleStep = 2;

} // namespace wisp
