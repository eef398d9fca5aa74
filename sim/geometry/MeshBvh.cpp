#include "sim/geometry/MeshBvh.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace wisp {

namespace {

// Binned SAH (Wald, "On fast construction of SAH-based bounding volume hierarchies", 2007):
// 16 bins per axis finds splits within a few percent of the full sweep at a fraction of the
// cost, which keeps a 270k-triangle head well under the interactive budget.
constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeafSize = 4; // leaves bigger than this are always split
constexpr float kTraversalCost = 1.0f; // relative to one triangle test
// SAH alone can peel one triangle off at a time on skewed inputs; past kMaxSahDepth the build
// switches to median splits, which bounds the depth by kMaxSahDepth + 32 and so the traversal
// stacks (one pending sibling per level) by kStackSize.
constexpr std::uint32_t kMaxSahDepth = 48;
constexpr int kStackSize = 96;

struct Box {
    glm::vec3 lo{ std::numeric_limits<float>::max() };
    glm::vec3 hi{ -std::numeric_limits<float>::max() };
    void grow(const glm::vec3& p)
    {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Box& b)
    {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool valid() const { return lo.x <= hi.x; }
    float halfArea() const
    {
        if (!valid())
            return 0.0f;
        const glm::vec3 e = hi - lo;
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

// The bin of a centroid coordinate `c` in [lo, lo + extent]. Written as a ratio, not as
// (c - lo) * (kBins / extent): for a subnormal extent kBins / extent is inf, and 0 * inf is NaN,
// whose int conversion indexed bins[INT_MIN]. The ratio of two finite numbers with c - lo <=
// extent is in [0, 1]; the clamp (NaN compares false, so it lands in bin 0) keeps every finite
// input in range whatever rounding does.
int binOf(float c, float lo, float extent)
{
    const float t = (c - lo) / extent * static_cast<float>(kBins);
    if (!(t > 0.0f))
        return 0;
    return t >= static_cast<float>(kBins - 1) ? kBins - 1 : static_cast<int>(t);
}

bool finite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

float boxDistance2(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi)
{
    const glm::vec3 d = glm::max(glm::max(lo - p, p - hi), glm::vec3(0.0f));
    return glm::dot(d, d);
}

} // namespace

MeshBvh::MeshBvh(const TriangleMesh& mesh)
{
    // What the build sorts: each triangle's box and centroid travel with it, so the binning and
    // partition passes stream through memory instead of gathering through an index.
    struct Ref {
        Box box;
        glm::vec3 centroid{ 0.0f };
        std::uint32_t id = 0;
    };
    const auto vertexCount = mesh.positions.size();
    std::vector<Ref> refs;
    refs.reserve(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        if (tri.x >= vertexCount || tri.y >= vertexCount || tri.z >= vertexCount)
            continue;
        if (!finite(mesh.positions[tri.x]) || !finite(mesh.positions[tri.y]) || !finite(mesh.positions[tri.z]))
            continue;
        Ref r;
        r.box.grow(mesh.positions[tri.x]);
        r.box.grow(mesh.positions[tri.y]);
        r.box.grow(mesh.positions[tri.z]);
        r.centroid = 0.5f * (r.box.lo + r.box.hi);
        r.id = static_cast<std::uint32_t>(t);
        refs.push_back(r);
    }
    if (refs.empty())
        return;

    struct Task {
        std::uint32_t node, begin, end, depth;
    };
    m_nodes.reserve(2 * refs.size());
    m_nodes.emplace_back();
    std::vector<Task> tasks{ { 0, 0, static_cast<std::uint32_t>(refs.size()), 0 } };

    struct Bin {
        Box box;
        std::uint32_t count = 0;
    };
    while (!tasks.empty()) {
        const Task task = tasks.back();
        tasks.pop_back();
        Box bounds, centroidBounds;
        for (std::uint32_t i = task.begin; i < task.end; ++i) {
            bounds.grow(refs[i].box);
            centroidBounds.grow(refs[i].centroid);
        }
        const std::uint32_t count = task.end - task.begin;
        Node& node = m_nodes[task.node];
        node.min = bounds.lo;
        node.max = bounds.hi;
        node.first = task.begin;
        node.count = count;
        if (count <= 2)
            continue;

        // Evaluate every axis' bins; keep the cheapest plane.
        float bestCost = std::numeric_limits<float>::max();
        int bestAxis = -1, bestPlane = 0;
        const glm::vec3 extent = centroidBounds.hi - centroidBounds.lo;
        for (int axis = 0; axis < 3 && task.depth < kMaxSahDepth; ++axis) {
            if (!(extent[axis] > 0.0f))
                continue;
            Bin bins[kBins];
            for (std::uint32_t i = task.begin; i < task.end; ++i) {
                const Ref& r = refs[i];
                const int b = binOf(r.centroid[axis], centroidBounds.lo[axis], extent[axis]);
                bins[b].box.grow(r.box);
                ++bins[b].count;
            }
            float rightArea[kBins];
            std::uint32_t rightCount[kBins];
            Box acc;
            std::uint32_t n = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.grow(bins[b].box);
                n += bins[b].count;
                rightArea[b] = acc.halfArea();
                rightCount[b] = n;
            }
            acc = Box{};
            n = 0;
            for (int plane = 1; plane < kBins; ++plane) { // plane p: bins [0, p) go left
                acc.grow(bins[plane - 1].box);
                n += bins[plane - 1].count;
                if (n == 0 || rightCount[plane] == 0)
                    continue;
                const float cost
                    = acc.halfArea() * static_cast<float>(n) + rightArea[plane] * static_cast<float>(rightCount[plane]);
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestPlane = plane;
                }
            }
        }

        std::uint32_t mid;
        if (bestAxis < 0) {
            // Too deep for SAH, or all centroids coincide: huge leaves would make every query
            // linear, so halve at the median of the widest centroid axis.
            if (count <= kMaxLeafSize)
                continue;
            const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
            mid = task.begin + count / 2;
            std::nth_element(refs.begin() + task.begin, refs.begin() + mid, refs.begin() + task.end,
                [&](const Ref& x, const Ref& y) { return x.centroid[axis] < y.centroid[axis]; });
        } else {
            const float parentArea = bounds.halfArea();
            const float splitCost = kTraversalCost + (parentArea > 0.0f ? bestCost / parentArea : 0.0f);
            if (count <= kMaxLeafSize && splitCost >= static_cast<float>(count))
                continue;
            const float lo = centroidBounds.lo[bestAxis];
            const float axisExtent = extent[bestAxis];
            const Ref* middle = std::partition(refs.data() + task.begin, refs.data() + task.end,
                [&](const Ref& r) { return binOf(r.centroid[bestAxis], lo, axisExtent) < bestPlane; });
            mid = static_cast<std::uint32_t>(middle - refs.data());
            if (mid == task.begin || mid == task.end)
                mid = task.begin + count / 2; // cannot happen with the counts above; stay safe
        }
        const auto left = static_cast<std::uint32_t>(m_nodes.size());
        // `node` may dangle after emplace_back: write through the index.
        m_nodes[task.node].first = left;
        m_nodes[task.node].count = 0;
        m_nodes.emplace_back();
        m_nodes.emplace_back();
        // Right first so the left subtree is built next and lands right after its parent.
        tasks.push_back({ left + 1, mid, task.end, task.depth + 1 });
        tasks.push_back({ left, task.begin, mid, task.depth + 1 });
    }

    m_corners.resize(3 * refs.size());
    m_triangleIds.resize(refs.size());
    for (std::size_t i = 0; i < refs.size(); ++i) {
        const glm::uvec3 tri = mesh.triangles[refs[i].id];
        m_corners[3 * i] = mesh.positions[tri.x];
        m_corners[3 * i + 1] = mesh.positions[tri.y];
        m_corners[3 * i + 2] = mesh.positions[tri.z];
        m_triangleIds[i] = refs[i].id;
    }
}

Aabb MeshBvh::bounds() const
{
    if (m_nodes.empty())
        return {};
    return { m_nodes[0].min, m_nodes[0].max };
}

MeshBvh::ClosestPoint MeshBvh::closestPoint(const glm::vec3& p) const
{
    if (auto found = closestPointWithin(p, std::numeric_limits<float>::infinity()))
        return *found;
    ClosestPoint none;
    none.point = p;
    none.distance = std::numeric_limits<float>::infinity();
    return none;
}

std::optional<MeshBvh::ClosestPoint> MeshBvh::closestPointWithin(const glm::vec3& p, float maxDistance) const
{
    if (m_nodes.empty() || !finite(p) || std::isnan(maxDistance) || maxDistance < 0.0f)
        return std::nullopt;
    // Searching with squared distances; best2 starts at the radius so anything farther is pruned.
    float best2 = std::isinf(maxDistance) ? std::numeric_limits<float>::infinity() : maxDistance * maxDistance;
    std::uint32_t bestIndex = std::numeric_limits<std::uint32_t>::max();
    TrianglePoint bestPoint;

    std::uint32_t stack[kStackSize];
    int top = 0;
    if (boxDistance2(p, m_nodes[0].min, m_nodes[0].max) > best2)
        return std::nullopt;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = m_nodes[stack[--top]];
        // Distances pushed earlier may be stale now that best2 shrank; recheck before the work.
        if (boxDistance2(p, node.min, node.max) > best2)
            continue;
        if (node.count > 0) {
            for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
                const TrianglePoint q
                    = closestPointOnTriangle(p, m_corners[3 * i], m_corners[3 * i + 1], m_corners[3 * i + 2]);
                const glm::vec3 d = q.point - p;
                const float d2 = glm::dot(d, d);
                if (d2 < best2 || (d2 == best2 && bestIndex == std::numeric_limits<std::uint32_t>::max())) {
                    best2 = d2;
                    bestIndex = i;
                    bestPoint = q;
                }
            }
            continue;
        }
        const Node& a = m_nodes[node.first];
        const Node& b = m_nodes[node.first + 1];
        const float da = boxDistance2(p, a.min, a.max);
        const float db = boxDistance2(p, b.min, b.max);
        // Push the farther child first so the nearer one is searched first and shrinks best2.
        const bool aFirst = da <= db;
        const float dFar = aFirst ? db : da, dNear = aFirst ? da : db;
        const std::uint32_t far = aFirst ? node.first + 1 : node.first;
        const std::uint32_t near = aFirst ? node.first : node.first + 1;
        if (dFar <= best2 && top < kStackSize)
            stack[top++] = far;
        if (dNear <= best2 && top < kStackSize)
            stack[top++] = near;
    }
    if (bestIndex == std::numeric_limits<std::uint32_t>::max())
        return std::nullopt;
    ClosestPoint result;
    result.surface.triangle = m_triangleIds[bestIndex];
    result.surface.barycentric = bestPoint.barycentric;
    result.point = bestPoint.point;
    result.distance = std::sqrt(best2);
    return result;
}

std::optional<MeshBvh::RayHit> MeshBvh::raycast(const glm::vec3& origin, const glm::vec3& direction, float maxT) const
{
    if (m_nodes.empty() || !finite(origin) || !finite(direction) || std::isnan(maxT) || maxT < 0.0f)
        return std::nullopt;
    if (direction == glm::vec3(0.0f))
        return std::nullopt;
    // Zero components would give inf * 0 = NaN in the slab test; a tiny stand-in keeps the
    // arithmetic finite and changes no answer that matters (the slabs are then effectively infinite).
    glm::vec3 slabDirection = direction;
    for (int a = 0; a < 3; ++a)
        if (std::abs(slabDirection[a]) < 1e-30f)
            slabDirection[a] = std::copysign(1e-30f, slabDirection[a]);
    const glm::vec3 inv = 1.0f / slabDirection;

    float bestT = maxT;
    std::uint32_t bestIndex = std::numeric_limits<std::uint32_t>::max();
    float bestU = 0.0f, bestV = 0.0f;
    auto enter = [&](const Node& n) {
        const glm::vec3 t0 = (n.min - origin) * inv, t1 = (n.max - origin) * inv;
        const glm::vec3 tNear = glm::min(t0, t1), tFar = glm::max(t0, t1);
        const float tEnter = std::max(std::max(tNear.x, tNear.y), std::max(tNear.z, 0.0f));
        const float tExit = std::min(std::min(tFar.x, tFar.y), std::min(tFar.z, bestT));
        return tEnter <= tExit ? tEnter : std::numeric_limits<float>::infinity();
    };

    std::uint32_t stack[kStackSize];
    float stackT[kStackSize];
    int top = 0;
    if (const float t = enter(m_nodes[0]); t != std::numeric_limits<float>::infinity()) {
        stack[top] = 0;
        stackT[top++] = t;
    }
    while (top > 0) {
        --top;
        if (stackT[top] > bestT)
            continue;
        const Node& node = m_nodes[stack[top]];
        if (node.count > 0) {
            for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
                // Möller–Trumbore, both faces (no culling on the determinant's sign).
                const glm::vec3 v0 = m_corners[3 * i];
                const glm::vec3 e1 = m_corners[3 * i + 1] - v0, e2 = m_corners[3 * i + 2] - v0;
                const glm::vec3 pv = glm::cross(direction, e2);
                const float det = glm::dot(e1, pv);
                if (det == 0.0f)
                    continue;
                const float invDet = 1.0f / det;
                const glm::vec3 tv = origin - v0;
                const float u = glm::dot(tv, pv) * invDet;
                if (u < 0.0f || u > 1.0f)
                    continue;
                const glm::vec3 qv = glm::cross(tv, e1);
                const float v = glm::dot(direction, qv) * invDet;
                if (v < 0.0f || u + v > 1.0f)
                    continue;
                const float t = glm::dot(e2, qv) * invDet;
                if (t >= 0.0f && t <= bestT && std::isfinite(t)
                    && (t < bestT || bestIndex == std::numeric_limits<std::uint32_t>::max())) {
                    bestT = t;
                    bestIndex = i;
                    bestU = u;
                    bestV = v;
                }
            }
            continue;
        }
        const float ta = enter(m_nodes[node.first]);
        const float tb = enter(m_nodes[node.first + 1]);
        const bool aFirst = ta <= tb;
        const float tNear = aFirst ? ta : tb, tFar = aFirst ? tb : ta;
        const std::uint32_t near = aFirst ? node.first : node.first + 1;
        const std::uint32_t far = aFirst ? node.first + 1 : node.first;
        if (tFar != std::numeric_limits<float>::infinity() && top < kStackSize) {
            stack[top] = far;
            stackT[top++] = tFar;
        }
        if (tNear != std::numeric_limits<float>::infinity() && top < kStackSize) {
            stack[top] = near;
            stackT[top++] = tNear;
        }
    }
    if (bestIndex == std::numeric_limits<std::uint32_t>::max())
        return std::nullopt;
    RayHit hit;
    hit.surface.triangle = m_triangleIds[bestIndex];
    hit.surface.barycentric = glm::vec2(bestU, bestV);
    hit.point = origin + bestT * direction;
    hit.t = bestT;
    return hit;
}

} // namespace wisp
