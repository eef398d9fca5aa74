// The SDF bake's band on SIMD lanes (sim/geometry/SdfBandRow.*): on every target the bake carries,
// each sample's squared distance to a triangle has the bits closestPointOnTriangle gives it, in every
// one of Ericson's regions and for degenerate triangles.
#include "sim/geometry/MeshBvh.h"
#include "sim/geometry/SdfBake.h"
#include "sim/geometry/SdfBandRow.h"
#include "sim/util/SimdTarget.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

namespace wisp {
namespace {

sdf_detail::BakeTriangle triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c)
{
    sdf_detail::BakeTriangle t;
    t.a = a;
    t.b = b;
    t.c = c;
    t.lo = glm::min(a, glm::min(b, c));
    t.hi = glm::max(a, glm::max(b, c));
    return t;
}

TEST(SdfBand, EveryTargetGivesTheScalarClosestPointsBits)
{
    std::mt19937 random(7);
    std::uniform_real_distribution<float> coordinate(-0.02f, 0.02f);
    auto point = [&] { return glm::vec3(coordinate(random), coordinate(random), coordinate(random)); };
    std::vector<sdf_detail::BakeTriangle> triangles;
    for (int n = 0; n < 40; ++n)
        triangles.push_back(triangle(point(), point(), point()));
    // Degenerate: collinear, a repeated corner, all three corners at one point.
    triangles.push_back(triangle({ 0, 0, 0 }, { 0.01f, 0, 0 }, { 0.02f, 0, 0 }));
    triangles.push_back(triangle({ 0, 0, 0 }, { 0, 0, 0 }, { 0, 0.01f, 0 }));
    triangles.push_back(triangle({ 0.003f, 0, 0 }, { 0.003f, 0, 0 }, { 0.003f, 0, 0 }));

    // Samples around each triangle, 37 of them (not a whole register: the tail counts too).
    constexpr std::size_t kSamples = 37;
    std::vector<float> xs(48), ys(48), zs(48);
    std::vector<std::uint32_t> indices(kSamples);
    for (std::size_t n = 0; n < kSamples; ++n)
        indices[n] = static_cast<std::uint32_t>(kSamples - 1 - n); // scattered: written where it says

    const std::vector<std::string> targets = availableSimdTargets();
    ASSERT_FALSE(targets.empty());
    std::size_t regionsSeen[3] = { 0, 0, 0 }; // corner, edge, face
    for (const sdf_detail::BakeTriangle& t : triangles) {
        for (std::size_t n = 0; n < kSamples; ++n) {
            const glm::vec3 p = point() * 1.5f;
            xs[n] = p.x;
            ys[n] = p.y;
            zs[n] = p.z;
        }
        std::vector<float> expected(kSamples);
        for (std::size_t n = 0; n < kSamples; ++n) {
            const glm::vec3 p(xs[n], ys[n], zs[n]);
            const TrianglePoint q = closestPointOnTriangle(p, t.a, t.b, t.c);
            const glm::vec3 d = q.point - p;
            expected[indices[n]] = glm::dot(d, d);
            const int zeros
                = (q.barycentric.x == 0.0f) + (q.barycentric.y == 0.0f) + (q.barycentric.x + q.barycentric.y == 1.0f);
            ++regionsSeen[zeros >= 2 ? 0 : zeros == 1 ? 1 : 2];
        }
        for (const std::string& target : targets) {
            ASSERT_EQ(forceSimdTarget(target), "");
            std::vector<float> values(kSamples, 1.0f); // above every distance here: all replaced
            sdf_detail::bandSamples(t, { xs.data(), ys.data(), zs.data(), indices.data(), kSamples }, values.data());
            EXPECT_EQ(std::memcmp(values.data(), expected.data(), kSamples * sizeof(float)), 0) << target;
            // A value already below is kept.
            std::vector<float> low(kSamples, 0.0f);
            sdf_detail::bandSamples(t, { xs.data(), ys.data(), zs.data(), indices.data(), kSamples }, low.data());
            EXPECT_EQ(low, std::vector<float>(kSamples, 0.0f)) << target;
        }
        forceSimdTarget("");
    }
    // Every kind of region was met.
    EXPECT_GT(regionsSeen[0], 50u);
    EXPECT_GT(regionsSeen[1], 50u);
    EXPECT_GT(regionsSeen[2], 50u);
}

} // namespace
} // namespace wisp
