#include "sim/style/StrandPicking.h"

#include "sim/groom/ScalpBrush.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

std::vector<StrandPick> strandsNearRay(const HairCurves& curves, std::span<const std::uint32_t> only,
    const glm::vec3& origin, const glm::vec3& direction, float radiusMetres, float falloff, float maxDepth)
{
    std::vector<StrandPick> picks;
    if (!(radiusMetres > 0.0f))
        return picks;
    const float r2 = radiusMetres * radiusMetres;
    auto visit = [&](std::uint32_t s) {
        float best = r2;
        float depth = 0.0f;
        for (const glm::vec3& p : curves.strand(s)) {
            const glm::vec3 v = p - origin;
            const float t = glm::dot(v, direction);
            if (t <= 0.0f || t > maxDepth)
                continue;
            const glm::vec3 across = v - t * direction;
            const float d2 = glm::dot(across, across);
            if (d2 < best) {
                best = d2;
                depth = t;
            }
        }
        if (best < r2) {
            const float weight = brushFalloff(std::sqrt(best) / radiusMetres, falloff);
            if (weight > 0.0f)
                picks.push_back({ s, weight, depth });
        }
    };
    if (only.empty())
        for (std::uint32_t s = 0; s < curves.strandCount(); ++s)
            visit(s);
    else
        for (std::uint32_t s : only)
            if (s < curves.strandCount())
                visit(s);
    return picks;
}

std::vector<StrandCut> strandsCutBy(const HairCurves& curves, const glm::vec3& eye, const glm::vec3& directionA,
    const glm::vec3& directionB, const std::function<bool(const glm::vec3&)>& visible)
{
    std::vector<StrandCut> cuts;
    const glm::vec3 normal = glm::cross(directionA, directionB);
    if (glm::length(normal) < 1e-7f)
        return cuts; // the cursor did not move: no blade
    const glm::vec3 n = glm::normalize(normal);
    for (std::uint32_t s = 0; s < curves.strandCount(); ++s) {
        const auto points = curves.strand(s);
        float arc = 0.0f;
        for (std::size_t j = 1; j < points.size(); ++j) {
            const glm::vec3 a = points[j - 1], b = points[j];
            const float segment = glm::distance(a, b);
            const float sa = glm::dot(a - eye, n), sb = glm::dot(b - eye, n);
            if ((sa > 0.0f) != (sb > 0.0f) && sa != sb) {
                const float t = sa / (sa - sb);
                const glm::vec3 x = a + t * (b - a);
                const glm::vec3 toX = x - eye;
                // Inside the wedge: between the two rays, in front of the eye.
                if (glm::dot(glm::cross(directionA, toX), n) >= 0.0f && glm::dot(glm::cross(toX, directionB), n) >= 0.0f
                    && glm::dot(toX, directionA + directionB) > 0.0f && (!visible || visible(x))) {
                    cuts.push_back({ s, arc + t * segment });
                    break;
                }
            }
            arc += segment;
        }
    }
    return cuts;
}

void combStrand(
    std::span<glm::vec3> positions, std::span<const float> segmentLengths, const glm::vec3& delta, float weight)
{
    const std::size_t n = positions.size();
    if (n < 2 || segmentLengths.size() + 1 != n)
        return;
    float total = 0.0f;
    for (float l : segmentLengths)
        total += l;
    float arc = 0.0f;
    for (std::size_t j = 1; j < n; ++j) {
        arc += segmentLengths[j - 1];
        positions[j] += delta * (weight * arc / std::max(total, 1e-9f));
    }
    for (std::size_t j = 1; j < n; ++j) {
        const glm::vec3 d = positions[j] - positions[j - 1];
        const float length = glm::length(d);
        if (length > 1e-9f)
            positions[j] = positions[j - 1] + d * (segmentLengths[j - 1] / length);
    }
}

float distanceToPolyline(const glm::vec3& p, std::span<const glm::vec3> line)
{
    float best = 1e30f;
    for (std::size_t j = 1; j < line.size(); ++j) {
        const glm::vec3 ab = line[j] - line[j - 1];
        const float t = std::clamp(glm::dot(p - line[j - 1], ab) / std::max(glm::dot(ab, ab), 1e-12f), 0.0f, 1.0f);
        best = std::min(best, glm::distance(p, line[j - 1] + t * ab));
    }
    return best;
}

glm::vec3 mirroredPoint(const glm::vec3& p, float planeX)
{
    return { 2.0f * planeX - p.x, p.y, p.z };
}
glm::vec3 mirroredDirection(const glm::vec3& d)
{
    return { -d.x, d.y, d.z };
}

} // namespace wisp
