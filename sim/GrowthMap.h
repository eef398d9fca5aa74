#pragma once
// Growth maps (the painted weights of Lee et al., one 0..1 value per vertex) that need no painting.

#include "sim/TriangleMesh.h"

#include <vector>

namespace wisp {

// For a head brought in without a painted map: hair on the upper part of the head, where the
// surface faces up or sideways, fading over a band so the edge is soft. Assumes +Y up.
std::vector<float> upperHeadGrowth(const TriangleMesh& head);

}  // namespace wisp
