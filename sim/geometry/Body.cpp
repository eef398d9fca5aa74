#include "sim/geometry/Body.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {
namespace {

// The built-in head's bounding box (DefaultHead.cpp; its neck column ends flat at y = -0.215).
constexpr glm::vec3 kDefaultMin{ -0.0842f, -0.2151f, -0.1063f };
constexpr glm::vec3 kDefaultMax{ 0.0841f, 0.1220f, 0.1137f };

// The bust for the built-in head, in its space. Sized from an adult's: shoulders 0.41 m across
// (biacromial breadth about 0.37 m plus the deltoids), their top 0.33 m below the crown; the neck
// 0.10 m thick (a little inside the head mesh's own neck, so only its part below shows); the upper
// chest and back 0.20 m deep, as deep as the head, so hair falling from the back of the head lands on it.
const Capsule kDefaultBody[] = {
    { { 0.0f, -0.080f, -0.019f }, { 0.0f, -0.250f, 0.001f }, 0.049f }, // neck, leaning forward as the mesh's
    { { -0.035f, -0.265f, -0.005f }, { -0.150f, -0.295f, -0.010f }, 0.055f }, // left shoulder, sloping down outward
    { { 0.035f, -0.265f, -0.005f }, { 0.150f, -0.295f, -0.010f }, 0.055f }, // right shoulder
    { { -0.090f, -0.345f, 0.000f }, { 0.090f, -0.345f, 0.000f }, 0.100f }, // upper chest and back
};

} // namespace

std::vector<Capsule> defaultBody(const TriangleMesh& head)
{
    if (!validateMesh(head).empty())
        return {};
    const Aabb box = boundsOf(head);
    const glm::vec3 size = box.size(), defaultSize = kDefaultMax - kDefaultMin;
    const float scale = 0.5f * (size.x / defaultSize.x + size.z / defaultSize.z);
    if (!(scale > 0.0f) || !std::isfinite(scale))
        return {};
    // Anchored at the top centre of the box: the crown is where every head's box is alike (a head
    // may or may not come with a neck, which moves the bottom).
    const glm::vec3 anchor(box.center().x, box.max.y, box.center().z);
    const glm::vec3 defaultAnchor(
        0.5f * (kDefaultMin.x + kDefaultMax.x), kDefaultMax.y, 0.5f * (kDefaultMin.z + kDefaultMax.z));
    std::vector<Capsule> body;
    for (const Capsule& c : kDefaultBody)
        body.push_back(
            { anchor + scale * (c.a - defaultAnchor), anchor + scale * (c.b - defaultAnchor), scale * c.radiusMetres });
    return body;
}

float capsuleDistance(const Capsule& c, const glm::vec3& p)
{
    const glm::vec3 ab = c.b - c.a;
    const float ab2 = glm::dot(ab, ab);
    const float u = ab2 > 0.0f ? std::clamp(glm::dot(p - c.a, ab) / ab2, 0.0f, 1.0f) : 0.0f;
    return glm::distance(p, c.a + u * ab) - c.radiusMetres;
}

TriangleMesh capsuleMesh(std::span<const Capsule> capsules, int around)
{
    TriangleMesh mesh;
    around = std::max(around, 3);
    const int half = std::max(around / 4, 2); // latitude rings per hemisphere, pole excluded
    for (const Capsule& c : capsules) {
        glm::vec3 axis = c.b - c.a;
        const float length = glm::length(axis);
        axis = length > 1e-9f ? axis / length : glm::vec3(0.0f, 1.0f, 0.0f);
        const glm::vec3 helper = std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 u = glm::normalize(glm::cross(helper, axis));
        const glm::vec3 v = glm::cross(axis, u);
        const auto first = static_cast<std::uint32_t>(mesh.positions.size());
        // South pole (at a, along -axis), rings from a's hemisphere to b's, north pole.
        mesh.positions.push_back(c.a - c.radiusMetres * axis);
        int rings = 0;
        for (int end = 0; end < 2; ++end) {
            const glm::vec3 centre = end == 0 ? c.a : c.b;
            for (int k = 0; k < half; ++k) {
                // Latitude from -90° (exclusive) to 0 at a, from 0 to 90° (exclusive) at b.
                const float t = end == 0 ? static_cast<float>(k + 1) / static_cast<float>(half)
                                         : static_cast<float>(k) / static_cast<float>(half);
                const float latitude = glm::half_pi<float>() * (end == 0 ? t - 1.0f : t);
                const float ringRadius = c.radiusMetres * std::cos(latitude);
                const glm::vec3 ringCentre = centre + c.radiusMetres * std::sin(latitude) * axis;
                for (int i = 0; i < around; ++i) {
                    const float phi = glm::two_pi<float>() * static_cast<float>(i) / static_cast<float>(around);
                    mesh.positions.push_back(ringCentre + ringRadius * (std::cos(phi) * u + std::sin(phi) * v));
                }
                ++rings;
            }
        }
        mesh.positions.push_back(c.b + c.radiusMetres * axis);
        const std::uint32_t south = first, north = static_cast<std::uint32_t>(mesh.positions.size() - 1);
        auto ring = [&](int r, int i) { return first + 1 + static_cast<std::uint32_t>(r * around + (i % around)); };
        // (u, v, axis) is right-handed, so rings run counter-clockwise seen from +axis.
        for (int i = 0; i < around; ++i) {
            mesh.triangles.push_back({ south, ring(0, i + 1), ring(0, i) });
            for (int r = 0; r + 1 < rings; ++r) {
                mesh.triangles.push_back({ ring(r, i), ring(r, i + 1), ring(r + 1, i + 1) });
                mesh.triangles.push_back({ ring(r, i), ring(r + 1, i + 1), ring(r + 1, i) });
            }
            mesh.triangles.push_back({ ring(rings - 1, i), ring(rings - 1, i + 1), north });
        }
    }
    return mesh;
}

} // namespace wisp
