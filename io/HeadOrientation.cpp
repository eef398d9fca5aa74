#include "io/HeadOrientation.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <vector>

namespace wisp::io {

namespace {

// How clear each fact must be (measured on the four shared heads: the mirror ratio is 0.0-0.52,
// the nose slab 0.07-0.16 of the head's width against 0.24-0.29 for the next narrowest, the
// cross-section above the nose 1.4-2.3 times the one below).
constexpr float kMirrorRatioMax = 0.8f; // best mirror error / second best
constexpr float kNoseSlabDepth = 0.04f; // of the left-right extent
constexpr float kNoseWidthMax = 0.3f; // nose slab width / left-right extent
constexpr float kNoseRatioMax = 0.6f; // nose slab width / next narrowest slab
constexpr float kSkullRatioMin = 1.15f; // cross-section above the nose / below it (or inverse)
constexpr std::size_t kMirrorSamples = 4000;

Axis axisOf(int index, int sign)
{
    return static_cast<Axis>(index * 2 + (sign < 0 ? 1 : 0));
}

int indexOf(Axis axis)
{
    return static_cast<int>(axis) / 2;
}

std::string formatRatio(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", value);
    return text;
}

// Mean distance from each sampled vertex mirrored across the plane through the box's centre
// perpendicular to `axis` to the nearest vertex, over a hash grid; distances are capped at 1.5
// cells (a vertex whose mirror image has nothing near it counts as that far off).
class MirrorError {
public:
    MirrorError(std::span<const glm::vec3> points, const glm::vec3& lo, const glm::vec3& hi)
        : m_points(points)
        , m_centre(0.5f * (lo + hi))
    {
        m_cell = std::max(glm::length(hi - lo) / 64.0f, std::numeric_limits<float>::min());
        for (std::size_t i = 0; i < points.size(); ++i)
            m_grid[key(cellOf(points[i]))].push_back(static_cast<std::uint32_t>(i));
    }

    double operator()(int axis) const
    {
        const std::size_t stride = std::max<std::size_t>(1, m_points.size() / kMirrorSamples);
        double sum = 0.0;
        std::size_t count = 0;
        for (std::size_t i = 0; i < m_points.size(); i += stride) {
            glm::vec3 q = m_points[i];
            q[axis] = 2.0f * m_centre[axis] - q[axis];
            sum += nearestDistance(q);
            ++count;
        }
        return count ? sum / double(count) / m_cell : 0.0;
    }

private:
    glm::ivec3 cellOf(const glm::vec3& p) const { return glm::ivec3(glm::floor((p - m_centre) / m_cell)); }
    static std::uint64_t key(const glm::ivec3& c)
    {
        const auto part = [](int v) { return std::uint64_t(std::uint32_t(v + (1 << 20)) & 0x1FFFFF); };
        return part(c.x) | (part(c.y) << 21) | (part(c.z) << 42);
    }
    float nearestDistance(const glm::vec3& q) const
    {
        const glm::ivec3 c = cellOf(q);
        float best2 = (1.5f * m_cell) * (1.5f * m_cell);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto found = m_grid.find(key(c + glm::ivec3(dx, dy, dz)));
                    if (found == m_grid.end())
                        continue;
                    for (std::uint32_t i : found->second) {
                        const glm::vec3 d = m_points[i] - q;
                        best2 = std::min(best2, glm::dot(d, d));
                    }
                }
        return std::sqrt(best2);
    }

    std::span<const glm::vec3> m_points;
    glm::vec3 m_centre;
    float m_cell = 1.0f;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> m_grid;
};

} // namespace

glm::vec3 axisVector(Axis axis)
{
    glm::vec3 v(0.0f);
    v[indexOf(axis)] = (static_cast<int>(axis) % 2) ? -1.0f : 1.0f;
    return v;
}

const char* axisName(Axis axis)
{
    static constexpr std::array<const char*, 6> names = { "+X", "-X", "+Y", "-Y", "+Z", "-Z" };
    return names[static_cast<std::size_t>(axis)];
}

std::optional<Axis> parseAxis(std::string_view text)
{
    int sign = 1;
    if (!text.empty() && (text.front() == '+' || text.front() == '-')) {
        sign = text.front() == '-' ? -1 : 1;
        text.remove_prefix(1);
    }
    if (text.size() != 1)
        return std::nullopt;
    const char c = static_cast<char>(text.front() | 0x20); // lower case
    if (c < 'x' || c > 'z')
        return std::nullopt;
    return axisOf(c - 'x', sign);
}

Axis defaultFront(Axis up)
{
    switch (up) {
    case Axis::PosY:
    case Axis::PosX:
    case Axis::NegX:
        return Axis::PosZ; // turns about Z (or none) leave Z alone
    case Axis::NegY:
        return Axis::NegZ; // half a turn about X
    case Axis::PosZ:
        return Axis::NegY; // -90 degrees about X: (x, y, z) -> (x, z, -y)
    case Axis::NegZ:
        return Axis::PosY; // +90 degrees about X: (x, y, z) -> (x, -z, y)
    }
    return Axis::PosZ;
}

glm::vec3 orient(const glm::vec3& p, Axis up, Axis front)
{
    const glm::vec3 u = axisVector(up), f = axisVector(front);
    // Rows of the rotation: Wisp's X = up x front (so that X x Y = Z), Y = up, Z = front.
    return { glm::dot(glm::cross(u, f), p), glm::dot(u, p), glm::dot(f, p) };
}

HeadOrientation detectHeadOrientation(std::span<const glm::vec3> positions)
{
    HeadOrientation result;
    if (positions.size() < 4) {
        result.reason = "too few vertices to tell which way is up";
        return result;
    }
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const glm::vec3& p : positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            result.reason = "a vertex is not a finite point";
            return result;
        }
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    // The grid below needs a finite, non-zero size (and the slabs a width).
    const float diagonal = glm::length(hi - lo);
    if (!(std::isfinite(diagonal) && diagonal > 0.0f && std::min({ hi.x - lo.x, hi.y - lo.y, hi.z - lo.z }) > 0.0f)) {
        result.reason = "the mesh is flat or has no finite extent";
        return result;
    }

    // 1. Left-right: the axis of best mirror symmetry.
    const MirrorError mirror(positions, lo, hi);
    std::array<double, 3> error{};
    for (int a = 0; a < 3; ++a)
        error[a] = mirror(a);
    std::array<int, 3> order{ 0, 1, 2 };
    std::sort(order.begin(), order.end(), [&](int a, int b) { return error[a] < error[b]; });
    const int lateral = order[0];
    if (!(error[order[0]] < kMirrorRatioMax * error[order[1]])) {
        result.reason = "no left-right mirror symmetry stands out, so it is not recognisably a head";
        return result;
    }
    const float width = hi[lateral] - lo[lateral];

    // 2. The face: the narrowest outermost slab among the four other directions.
    struct Slab {
        int axis = 0;
        int sign = 1;
        float widthRatio = 0.0f;
        glm::vec3 tip{ 0.0f };
    };
    std::vector<Slab> slabs;
    for (int a = 0; a < 3; ++a) {
        if (a == lateral)
            continue;
        for (int sign : { 1, -1 }) {
            float extreme = std::numeric_limits<float>::lowest();
            glm::vec3 tip(0.0f);
            for (const glm::vec3& p : positions)
                if (sign * p[a] > extreme) {
                    extreme = sign * p[a];
                    tip = p;
                }
            float l = std::numeric_limits<float>::max(), h = std::numeric_limits<float>::lowest();
            for (const glm::vec3& p : positions)
                if (sign * p[a] >= extreme - kNoseSlabDepth * width) {
                    l = std::min(l, p[lateral]);
                    h = std::max(h, p[lateral]);
                }
            slabs.push_back({ a, sign, (h - l) / width, tip });
        }
    }
    std::sort(slabs.begin(), slabs.end(), [](const Slab& a, const Slab& b) { return a.widthRatio < b.widthRatio; });
    const Slab& nose = slabs[0];
    if (!(nose.widthRatio < kNoseWidthMax && nose.widthRatio < kNoseRatioMax * slabs[1].widthRatio)) {
        result.reason = "no nose-like narrow tip stands out (narrowest end " + formatRatio(nose.widthRatio)
            + " of the width, next " + formatRatio(slabs[1].widthRatio) + ")";
        return result;
    }

    // 3. Up: the side of the nose where the cross-section is larger (the skull, not the jaw and neck).
    const int vertical = 3 - lateral - nose.axis;
    const float noseLevel = nose.tip[vertical];
    float nl = std::numeric_limits<float>::max(), nh = std::numeric_limits<float>::lowest();
    for (const glm::vec3& p : positions)
        if (std::abs(p[vertical] - noseLevel) < 0.05f * width) {
            nl = std::min(nl, p[lateral]);
            nh = std::max(nh, p[lateral]);
        }
    const float window = 0.6f * (nh - nl);
    constexpr int kSlices = 8;
    struct Extent {
        glm::vec2 lo{ std::numeric_limits<float>::max() };
        glm::vec2 hi{ std::numeric_limits<float>::lowest() };
    };
    std::array<Extent, 2 * kSlices> slices{};
    for (const glm::vec3& p : positions) {
        const float t = (p[vertical] - (noseLevel - window)) / (2.0f * window) * float(2 * kSlices);
        if (!(t >= 0.0f && t < float(2 * kSlices)))
            continue;
        Extent& e = slices[static_cast<std::size_t>(t)];
        const glm::vec2 q(p[lateral], p[nose.axis]);
        e.lo = glm::min(e.lo, q);
        e.hi = glm::max(e.hi, q);
    }
    double below = 0.0, above = 0.0;
    for (int i = 0; i < 2 * kSlices; ++i) {
        const Extent& e = slices[static_cast<std::size_t>(i)];
        if (e.hi.x < e.lo.x)
            continue;
        (i < kSlices ? below : above) += double(e.hi.x - e.lo.x) * double(e.hi.y - e.lo.y);
    }
    const double ratio = above / std::max(below, 1e-30);
    if (!(ratio > kSkullRatioMin || ratio < 1.0 / kSkullRatioMin)) {
        result.reason
            = "cannot tell the skull from the jaw around the nose (cross-sections " + formatRatio(ratio) + " to 1)";
        return result;
    }
    const int upSign = ratio > 1.0 ? 1 : -1;
    result.up = axisOf(vertical, upSign);
    result.front = axisOf(nose.axis, nose.sign);
    result.found = true;
    result.reason = std::string("mirror-symmetric across ") + "XYZ"[lateral] + ", the nose points "
        + axisName(result.front) + ", the skull is on the " + axisName(result.up) + " side";
    return result;
}

float skullWidth(std::span<const glm::vec3> upright)
{
    if (upright.empty())
        return 0.0f;
    // Vertices from the top down, with the running left-right extent, so that width(d) is a lookup.
    std::vector<std::uint32_t> order(upright.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(
        order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return upright[a].y > upright[b].y; });
    std::vector<float> spanDown(order.size());
    float l = std::numeric_limits<float>::max(), h = std::numeric_limits<float>::lowest();
    for (std::size_t i = 0; i < order.size(); ++i) {
        l = std::min(l, upright[order[i]].x);
        h = std::max(h, upright[order[i]].x);
        spanDown[i] = h - l;
    }
    const float top = upright[order.front()].y, height = top - upright[order.back()].y;
    const auto widthAt = [&](float depth) {
        const auto end = std::partition_point(
            order.begin(), order.end(), [&](std::uint32_t i) { return upright[i].y >= top - depth; });
        return end == order.begin() ? 0.0f : spanDown[static_cast<std::size_t>(end - order.begin()) - 1];
    };
    // width(d) grows with d; from a thin band, d <- width(d) climbs to the first d with width(d) <= d.
    float depth = 0.1f * height;
    float width = widthAt(depth);
    for (int i = 0; i < 64 && width > depth && depth < height; ++i) {
        depth = std::min(width, height);
        width = widthAt(depth);
    }
    return width;
}

} // namespace wisp::io
