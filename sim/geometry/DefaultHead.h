#pragma once
// Wisp's built-in head: made here, procedurally, so the editor opens on something to groom
// without any external asset.

#include "sim/geometry/TriangleMesh.h"

#include <vector>

namespace wisp {

struct DefaultHead {
    TriangleMesh mesh; // metres, +Y up, face looks toward +Z
    std::vector<float> growthWeights; // one per vertex, 0..1: where hair grows (the painted growth map of Lee et al.)
};

// Deterministic: the same mesh and weights on every call and every machine. Takes well under 100 ms.
DefaultHead makeDefaultHead();

} // namespace wisp
