#pragma once
// The shortest-arc rotation between two directions, the one helper for every parallel transport
// (the groom's curl frames and member offsets, the solver's rest frames, the rest-shape solve's
// turns). Rodrigues' formula: with k = a x b and c = a . b, the rotation taking unit a onto unit b
// about k is R v = v c + k x v + k (k . v) / (1 + c).
//
// Edge cases, stated once: a == b turns nothing; a == -b has no unique shortest arc, and
// rotateShortestArc takes the half-turn about anyPerpendicular(a) (so a still lands on b), while
// turnShortestArc, which turns only part of the way, leaves v as it is there.

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace wisp {

// A unit vector across unit n, chosen the same way every time (the helper axis +Y, or +X when n is
// near +-Y).
glm::vec3 anyPerpendicular(const glm::vec3& n);

// v rotated by the rotation taking unit a onto unit b by the shortest arc.
glm::vec3 rotateShortestArc(const glm::vec3& a, const glm::vec3& b, const glm::vec3& v);
// The same rotation as a matrix.
glm::mat3 shortestArcMatrix(const glm::vec3& a, const glm::vec3& b);

// v turned about a x b by `share` of the angle from unit a to unit b, by at most maxRadians. For a
// and b parallel or antiparallel (|a x b| < 1e-7) v is returned unchanged.
glm::vec3 turnShortestArc(
    const glm::vec3& a, const glm::vec3& b, const glm::vec3& v, float share, float maxRadians = 3.2f);

} // namespace wisp
