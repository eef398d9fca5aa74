#pragma once
// A bounding volume hierarchy over a triangle mesh: exact closest points (to place roots, to
// snap brushes to the scalp) and ray casts (picking in the viewport, growing strands outward).
//
// Built with binned SAH splits into one flat node array; queries walk it with a small fixed
// stack, so they never allocate and are safe to run from many threads at once. The BVH keeps
// its own copy of the triangles' corners, so the mesh it was built from may be destroyed.

#include "sim/geometry/TriangleMesh.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace wisp {

// The point of triangle (a, b, c) nearest to p, with its barycentric weights (b1, b2) of b and c
// (Ericson, Real-Time Collision Detection, 5.1.5: Voronoi regions, no square roots). Zero-area
// triangles fall back to their nearest edge, so the result is always finite for finite input.
// Inline because the SDF bake calls it tens of millions of times.
struct TrianglePoint {
    glm::vec3 point{ 0.0f };
    glm::vec2 barycentric{ 0.0f };
};
inline TrianglePoint closestPointOnSegment(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b)
{
    const glm::vec3 ab = b - a;
    const float len2 = glm::dot(ab, ab);
    float t = len2 > 0.0f ? glm::dot(p - a, ab) / len2 : 0.0f;
    t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
    return { a + t * ab, glm::vec2(t, 0.0f) };
}
inline TrianglePoint closestPointOnTriangle(
    const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c)
{
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f)
        return { a, glm::vec2(0.0f, 0.0f) };
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3)
        return { b, glm::vec2(1.0f, 0.0f) };
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
        const float den = d1 - d3;
        const float v = den > 0.0f ? d1 / den : 0.0f;
        return { a + v * ab, glm::vec2(v, 0.0f) };
    }
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6)
        return { c, glm::vec2(0.0f, 1.0f) };
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        const float den = d2 - d6;
        const float w = den > 0.0f ? d2 / den : 0.0f;
        return { a + w * ac, glm::vec2(0.0f, w) };
    }
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
        const float den = (d4 - d3) + (d5 - d6);
        const float w = den > 0.0f ? (d4 - d3) / den : 0.0f;
        return { b + w * (c - b), glm::vec2(1.0f - w, w) };
    }
    const float den = va + vb + vc;
    if (den > 0.0f) {
        const float v = vb / den, w = vc / den;
        return { a + v * ab + w * ac, glm::vec2(v, w) };
    }
    // Degenerate (collinear corners): the nearest of the three edges.
    TrianglePoint best = closestPointOnSegment(p, a, b); // (t, 0) is already (b1, b2) for edge ab
    float bestD2 = glm::dot(p - best.point, p - best.point);
    TrianglePoint e = closestPointOnSegment(p, a, c);
    if (const float d2e = glm::dot(p - e.point, p - e.point); d2e < bestD2) {
        best = { e.point, glm::vec2(0.0f, e.barycentric.x) };
        bestD2 = d2e;
    }
    e = closestPointOnSegment(p, b, c);
    if (const float d2e = glm::dot(p - e.point, p - e.point); d2e < bestD2)
        best = { e.point, glm::vec2(1.0f - e.barycentric.x, e.barycentric.x) };
    return best;
}

class MeshBvh {
public:
    MeshBvh() = default;
    // Triangles with an index out of range or a non-finite corner are left out (they could only
    // poison the boxes); zero-area triangles are kept, queries handle them.
    explicit MeshBvh(const TriangleMesh& mesh);

    bool empty() const { return m_nodes.empty(); }
    std::size_t triangleCount() const { return m_triangleIds.size(); }
    std::size_t nodeCount() const { return m_nodes.size(); }
    Aabb bounds() const; // zero box when empty

    struct ClosestPoint {
        SurfacePoint surface; // triangle index of the original mesh, barycentric (b1, b2)
        glm::vec3 point{ 0.0f }; // metres
        float distance = 0.0f; // metres; +infinity when the BVH is empty
    };
    // The exact nearest point on the mesh (unsigned distance).
    ClosestPoint closestPoint(const glm::vec3& p) const;
    // As closestPoint, but gives up (nullopt) when nothing lies within maxDistance metres; cheaper
    // when the caller only cares about a neighbourhood.
    std::optional<ClosestPoint> closestPointWithin(const glm::vec3& p, float maxDistance) const;

    struct RayHit {
        SurfacePoint surface;
        glm::vec3 point{ 0.0f };
        float t = 0.0f; // hit = origin + t * direction (direction need not be unit length)
    };
    // The nearest hit with 0 <= t <= maxT, front or back faces alike (Möller–Trumbore).
    std::optional<RayHit> raycast(const glm::vec3& origin, const glm::vec3& direction, float maxT) const;

private:
    // 32 bytes, two to a cache line. Leaves: count > 0 triangles from `first` in m_corners order.
    // Inner nodes: count == 0, children at `first` and `first + 1`.
    struct Node {
        glm::vec3 min{ 0.0f };
        std::uint32_t first = 0;
        glm::vec3 max{ 0.0f };
        std::uint32_t count = 0;
    };

    std::vector<Node> m_nodes;
    std::vector<glm::vec3> m_corners; // three per triangle, in leaf order
    std::vector<std::uint32_t> m_triangleIds; // leaf order -> triangle index in the source mesh
};

} // namespace wisp
