#pragma once
// Growth maps (the painted weights of Lee et al., one 0..1 value per vertex) that need no painting.

#include "sim/geometry/TriangleMesh.h"

#include <vector>

namespace wisp {

// Where hair grows on a head that came without a painted map: the scalp. The head is placed
// (metres, +Y up, face toward +Z; io/HeadPlacement.h). Landmarks are the top of the head and the
// nose tip (the vertex furthest toward +Z near the middle, within 0.3 m of the top, so a bust's
// chest is not taken for it); with H the height from the nose tip to the top, the hairline runs
//     at the front (forehead)  H * 0.67 above the nose tip  (about 5 cm below the top),
//     over the ears            H * 0.45 above it            (the top of the ear),
//     at the back (nape)       H * 0.10 below it,
// linearly in between along the depth of the head, after the usual proportions of an adult head
// (hairline, brow, nose base and chin about a third of the face apart). Weights fade in over
// H * 0.1 above that line, and out where the surface faces down (under the chin, the occiput's
// underside). No hair on the face, the ears, the neck's front or a bust.
std::vector<float> scalpGrowth(const TriangleMesh& head);

} // namespace wisp
