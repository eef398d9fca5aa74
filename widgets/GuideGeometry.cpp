#include "widgets/GuideGeometry.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {
namespace {

bool finite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Two unit vectors perpendicular to `axis` and to each other.
void basisAround(const glm::vec3& axis, glm::vec3& u, glm::vec3& v)
{
    const glm::vec3 helper = std::abs(axis.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    u = glm::normalize(glm::cross(axis, helper));
    v = glm::cross(axis, u);
}

// A ring as GL_TRIANGLES: two per segment, between the inner and the outer edge of the band.
void appendRing(std::vector<GuideVertex>& out, const glm::vec3& centre, const glm::vec3& normal, float radiusMetres,
    float bandMetres, const glm::vec4& colour)
{
    const float normalLength = glm::length(normal);
    if (!finite(centre) || !finite(normal) || !(normalLength > 1e-6f) || !std::isfinite(bandMetres))
        return;
    const glm::vec3 axis = normal / normalLength;
    glm::vec3 u, v;
    basisAround(axis, u, v);
    const glm::vec3 lifted = centre + axis * kBrushRingLiftMetres;
    const float halfBand = 0.5f * std::max(bandMetres, 0.0f);
    const float inner = std::max(radiusMetres - halfBand, 0.0f);
    const float outer = radiusMetres + halfBand;
    const glm::vec3 none{ 0.0f }; // unlit
    auto edge = [&](int i, float radius) {
        const float a = glm::two_pi<float>() * static_cast<float>(i) / kBrushRingSegments;
        return GuideVertex{ lifted + radius * (std::cos(a) * u + std::sin(a) * v), none, colour };
    };
    for (int i = 0; i < kBrushRingSegments; ++i) {
        const GuideVertex in0 = edge(i, inner), out0 = edge(i, outer);
        const GuideVertex in1 = edge(i + 1, inner), out1 = edge(i + 1, outer);
        out.insert(out.end(), { in0, out0, out1, in0, out1, in1 });
    }
}

} // namespace

std::vector<GuideVertex> buildBrushRings(const BrushCursor& cursor, float bandMetres, float mirrorBandMetres)
{
    std::vector<GuideVertex> triangles;
    if (!std::isfinite(cursor.radiusMetres) || !(cursor.radiusMetres > 0.0f))
        return triangles;
    // sRGB: white adds; a light red (still bright against skin and dark hair) erases.
    const glm::vec3 colour = cursor.erase ? glm::vec3(1.0f, 0.32f, 0.28f) : glm::vec3(1.0f);
    appendRing(triangles, cursor.centre, cursor.normal, cursor.radiusMetres, bandMetres, glm::vec4(colour, 1.0f));
    if (cursor.mirrored)
        appendRing(triangles, cursor.mirrorCentre, cursor.mirrorNormal, cursor.radiusMetres, mirrorBandMetres,
            glm::vec4(colour, 0.45f));
    if (cursor.dryer) {
        const std::vector<GuideVertex> cone
            = buildDryerCone(cursor.dryerNozzle, cursor.centre, cursor.dryerHalfAngleRadians, bandMetres, 1.0f);
        triangles.insert(triangles.end(), cone.begin(), cone.end());
        if (cursor.mirrored) {
            // The nozzle's offset from the aim, mirrored across x like the ring.
            const glm::vec3 offset = cursor.dryerNozzle - cursor.centre;
            const glm::vec3 mirrorNozzle = cursor.mirrorCentre + glm::vec3(-offset.x, offset.y, offset.z);
            const std::vector<GuideVertex> mirror = buildDryerCone(
                mirrorNozzle, cursor.mirrorCentre, cursor.dryerHalfAngleRadians, mirrorBandMetres, 0.45f);
            triangles.insert(triangles.end(), mirror.begin(), mirror.end());
        }
    }
    return triangles;
}

std::vector<GuideVertex> buildDryerCone(
    const glm::vec3& nozzle, const glm::vec3& aim, float halfAngleRadians, float bandMetres, float alpha)
{
    std::vector<GuideVertex> out;
    const glm::vec3 along = aim - nozzle;
    const float length = glm::length(along);
    if (!finite(nozzle) || !finite(aim) || !(length > 1e-5f) || !std::isfinite(halfAngleRadians)
        || !std::isfinite(bandMetres))
        return out;
    const glm::vec3 axis = along / length;
    glm::vec3 u, v;
    basisAround(axis, u, v);
    const float rim = length * std::tan(std::clamp(halfAngleRadians, 0.01f, 1.4f));
    const glm::vec3 none{ 0.0f }; // unlit
    // The air: pale blue, mostly see-through, so the hair under it stays visible.
    const glm::vec4 air{ 0.55f, 0.80f, 1.0f, 0.16f * alpha };
    const glm::vec4 edge{ 0.70f, 0.88f, 1.0f, 0.85f * alpha };
    const auto around = [&](float angle) { return std::cos(angle) * u + std::sin(angle) * v; };
    for (int i = 0; i < kDryerConeSides; ++i) {
        const float a0 = glm::two_pi<float>() * static_cast<float>(i) / kDryerConeSides;
        const float a1 = glm::two_pi<float>() * static_cast<float>(i + 1) / kDryerConeSides;
        out.insert(out.end(),
            { { nozzle, none, air }, { aim + rim * around(a0), none, air }, { aim + rim * around(a1), none, air } });
    }
    // The edges: thin quads from the nozzle to the rim, facing the axis' sideways direction.
    const float halfBand = 0.5f * std::max(bandMetres, 0.0f);
    for (int i = 0; i < kDryerConeEdges; ++i) {
        const float a = glm::two_pi<float>() * static_cast<float>(i) / kDryerConeEdges;
        const glm::vec3 out0 = around(a);
        const glm::vec3 side = glm::cross(axis, out0) * halfBand;
        const glm::vec3 tip = aim + rim * out0;
        out.insert(
            out.end(), { { nozzle - side, none, edge }, { tip - side, none, edge }, { tip + side, none, edge } });
        out.insert(
            out.end(), { { nozzle - side, none, edge }, { tip + side, none, edge }, { nozzle + side, none, edge } });
    }
    // The nozzle: a small bright disc where the air leaves the dryer.
    const float nozzleRadius = std::max(2.0f * halfBand, 0.004f);
    for (int i = 0; i < kDryerConeSides; ++i) {
        const float a0 = glm::two_pi<float>() * static_cast<float>(i) / kDryerConeSides;
        const float a1 = glm::two_pi<float>() * static_cast<float>(i + 1) / kDryerConeSides;
        out.insert(out.end(),
            { { nozzle, none, edge }, { nozzle + nozzleRadius * around(a0), none, edge },
                { nozzle + nozzleRadius * around(a1), none, edge } });
    }
    return out;
}

GroundGrid buildGroundGrid(const Aabb& head)
{
    GroundGrid grid;
    if (!finite(head.min) || !finite(head.max))
        return grid;
    constexpr float kSpacing = 0.05f; // metres
    constexpr int kMajorEvery = 5;
    const float halfExtent = std::clamp(2.5f * std::max(head.size().x, head.size().z), 0.4f, 5.0f);
    const int halfLines = static_cast<int>(std::ceil(halfExtent / kSpacing));
    // Snap the centre to the grid, so lines stay on world coordinates as heads change.
    const glm::vec3 c = head.center();
    grid.centre = { std::round(c.x / kSpacing) * kSpacing, head.min.y, std::round(c.z / kSpacing) * kSpacing };
    grid.fadeRadiusMetres = halfLines * kSpacing;

    const glm::vec4 minor{ 0.55f, 0.57f, 0.62f, 0.22f };
    const glm::vec4 major{ 0.62f, 0.64f, 0.70f, 0.42f };
    const glm::vec4 xAxis{ 0.85f, 0.32f, 0.32f, 0.65f }; // the line z = 0 runs along X
    const glm::vec4 zAxis{ 0.32f, 0.48f, 0.90f, 0.65f }; // the line x = 0 runs along Z
    const float reach = halfLines * kSpacing;
    const glm::vec3 none{ 0.0f };
    for (int i = -halfLines; i <= halfLines; ++i) {
        const float offset = i * kSpacing;
        const float x = grid.centre.x + offset;
        const float z = grid.centre.z + offset;
        const int worldX = static_cast<int>(std::lround(x / kSpacing));
        const int worldZ = static_cast<int>(std::lround(z / kSpacing));
        const glm::vec4 alongZ = worldX == 0 ? zAxis : (worldX % kMajorEvery == 0 ? major : minor);
        const glm::vec4 alongX = worldZ == 0 ? xAxis : (worldZ % kMajorEvery == 0 ? major : minor);
        grid.lines.push_back({ { x, grid.centre.y, grid.centre.z - reach }, none, alongZ });
        grid.lines.push_back({ { x, grid.centre.y, grid.centre.z + reach }, none, alongZ });
        grid.lines.push_back({ { grid.centre.x - reach, grid.centre.y, z }, none, alongX });
        grid.lines.push_back({ { grid.centre.x + reach, grid.centre.y, z }, none, alongX });
    }
    return grid;
}

WindArrow buildWindArrow(const Aabb& head, const glm::vec3& windMetresPerSecond)
{
    WindArrow arrow;
    const float speed = glm::length(windMetresPerSecond);
    if (!finite(windMetresPerSecond) || !std::isfinite(speed) || speed < kStillAirMetresPerSecond || !finite(head.min)
        || !finite(head.max))
        return arrow;
    const glm::vec3 direction = windMetresPerSecond / speed;
    const float length
        = std::clamp(kWindArrowMinMetres + kWindArrowMetresPerMps * speed, kWindArrowMinMetres, kWindArrowMaxMetres);
    // Aim at the upper head, where the hair is; stop a little outside the head's half-width.
    const glm::vec3 size = head.size();
    const glm::vec3 target = head.center() + glm::vec3(0.0f, 0.25f * size.y, 0.0f);
    const float clearance = 0.5f * std::max({ size.x, size.z, 0.05f }) + 0.06f;
    arrow.tip = target - direction * clearance;
    arrow.tail = arrow.tip - direction * length;
    arrow.visible = true;

    constexpr int kSides = 20;
    const float shaftRadius = 0.0035f;
    const float coneRadius = 0.010f;
    const float coneLength = std::min(0.028f, 0.45f * length);
    const glm::vec3 coneBase = arrow.tip - direction * coneLength;
    const glm::vec4 colour{ 0.45f, 0.78f, 1.0f, 1.0f };
    glm::vec3 u, v;
    basisAround(direction, u, v);
    auto ring = [&](int i) {
        const float a = glm::two_pi<float>() * static_cast<float>(i) / kSides;
        return std::cos(a) * u + std::sin(a) * v;
    };
    // The cone's side normal leans toward the tip by the cone's slope.
    const float slope = coneRadius / coneLength;
    auto& t = arrow.triangles;
    for (int i = 0; i < kSides; ++i) {
        const glm::vec3 r0 = ring(i), r1 = ring(i + 1);
        // Shaft side (two triangles) and its back cap.
        const glm::vec3 a0 = arrow.tail + r0 * shaftRadius, a1 = arrow.tail + r1 * shaftRadius;
        const glm::vec3 b0 = coneBase + r0 * shaftRadius, b1 = coneBase + r1 * shaftRadius;
        t.insert(t.end(), { { a0, r0, colour }, { b0, r0, colour }, { b1, r1, colour } });
        t.insert(t.end(), { { a0, r0, colour }, { b1, r1, colour }, { a1, r1, colour } });
        t.insert(
            t.end(), { { arrow.tail, -direction, colour }, { a1, -direction, colour }, { a0, -direction, colour } });
        // Cone side and its base.
        const glm::vec3 c0 = coneBase + r0 * coneRadius, c1 = coneBase + r1 * coneRadius;
        const glm::vec3 n0 = glm::normalize(r0 + slope * direction), n1 = glm::normalize(r1 + slope * direction);
        const glm::vec3 nTip = glm::normalize(ring(i) + ring(i + 1) + 2.0f * slope * direction);
        t.insert(t.end(), { { c0, n0, colour }, { arrow.tip, nTip, colour }, { c1, n1, colour } });
        t.insert(t.end(), { { coneBase, -direction, colour }, { c1, -direction, colour }, { c0, -direction, colour } });
    }
    return arrow;
}

} // namespace wisp
