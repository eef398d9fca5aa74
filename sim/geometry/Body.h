#pragma once
// A bust under the head: the neck, the shoulders and the upper chest and back as capsules (head
// space, metres), for the solver to collide the hair with (the `body` parameter) and for the
// viewport to draw. The editor and wisp-cli take the body from here, so both collide with the same one.

#include "sim/geometry/TriangleMesh.h"
#include "sim/solver/Solver.h"

#include <span>
#include <vector>

namespace wisp {

// The body for `head`, placed from its bounding box: designed for the built-in head (0.17 m wide,
// 0.22 m deep, crown at the top of its box; neck column to 0.34 m below the crown) and, for
// any other head, moved to the top centre of its box and scaled by its width and depth against the
// built-in one's. Order: neck, left shoulder (-X), right shoulder (+X), upper chest and back.
// Empty for a head with no usable bounds (see validateMesh).
std::vector<Capsule> defaultBody(const TriangleMesh& head);

// The indices of defaultBody's capsules.
enum BodyCapsule : std::size_t { kBodyNeck = 0, kBodyLeftShoulder = 1, kBodyRightShoulder = 2, kBodyChest = 3 };

// Distance from `p` to the capsule's surface (negative inside), metres.
float capsuleDistance(const Capsule& capsule, const glm::vec3& p);

// A closed triangle mesh of the capsules (each its own closed surface, counter-clockwise seen from
// outside), `around` vertices around each ring; for drawing.
TriangleMesh capsuleMesh(std::span<const Capsule> capsules, int around = 32);

} // namespace wisp
