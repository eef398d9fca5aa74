#include "sim/geometry/MeshBvh.h"
#include "MeshFixtures.h"
#include "sim/geometry/TriangleMesh.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>

namespace wisp {
namespace {

using test::makeIcosphere;
using test::planckPath;
using test::readObj;

// Max Planck's head in metres (the OBJ is in millimetres), or an empty mesh when the assets
// folder is not there.
TriangleMesh planckHead()
{
    TriangleMesh mesh;
    if (std::filesystem::exists(planckPath()))
        mesh = readObj(planckPath(), 0.001f);
    return mesh;
}

struct BruteClosest {
    float distance = std::numeric_limits<float>::infinity();
    std::uint32_t triangle = 0;
};
BruteClosest bruteClosest(const TriangleMesh& mesh, const glm::vec3& p)
{
    BruteClosest best;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        const TrianglePoint q
            = closestPointOnTriangle(p, mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z]);
        const float d = glm::length(q.point - p);
        if (d < best.distance)
            best = { d, t };
    }
    return best;
}

// Möller–Trumbore over every triangle, both faces: the reference for raycast().
std::optional<float> bruteRaycast(const TriangleMesh& mesh, const glm::vec3& o, const glm::vec3& d, float maxT)
{
    std::optional<float> best;
    for (const glm::uvec3& tri : mesh.triangles) {
        const glm::vec3 v0 = mesh.positions[tri.x];
        const glm::vec3 e1 = mesh.positions[tri.y] - v0, e2 = mesh.positions[tri.z] - v0;
        const glm::vec3 pv = glm::cross(d, e2);
        const float det = glm::dot(e1, pv);
        if (det == 0.0f)
            continue;
        const glm::vec3 tv = o - v0;
        const float u = glm::dot(tv, pv) / det;
        if (u < 0.0f || u > 1.0f)
            continue;
        const glm::vec3 qv = glm::cross(tv, e1);
        const float v = glm::dot(d, qv) / det;
        if (v < 0.0f || u + v > 1.0f)
            continue;
        const float t = glm::dot(e2, qv) / det;
        if (t >= 0.0f && t <= maxT && (!best || t < *best))
            best = t;
    }
    return best;
}

void expectClosestMatchesBruteForce(const TriangleMesh& mesh, int samples, float grow, unsigned seed)
{
    const MeshBvh bvh(mesh);
    ASSERT_FALSE(bvh.empty());
    const Aabb box = boundsOf(mesh);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> ux(box.min.x - grow, box.max.x + grow),
        uy(box.min.y - grow, box.max.y + grow), uz(box.min.z - grow, box.max.z + grow);
    for (int i = 0; i < samples; ++i) {
        const glm::vec3 p(ux(rng), uy(rng), uz(rng));
        const BruteClosest expected = bruteClosest(mesh, p);
        const MeshBvh::ClosestPoint got = bvh.closestPoint(p);
        ASSERT_NEAR(got.distance, expected.distance, 1e-6f) << "sample " << i;
        // The reported point is on the reported triangle at the reported barycentrics, and at the
        // reported distance (ties between triangles may pick either, so the triangle is not compared).
        EXPECT_NEAR(glm::length(pointOn(mesh, got.surface) - got.point), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(got.point - p), got.distance, 1e-6f);
        EXPECT_GE(got.surface.barycentric.x, 0.0f);
        EXPECT_GE(got.surface.barycentric.y, 0.0f);
        EXPECT_LE(got.surface.barycentric.x + got.surface.barycentric.y, 1.0f + 1e-5f);
    }
}

TEST(MeshBvh, ClosestPointMatchesBruteForceOnSphere)
{
    expectClosestMatchesBruteForce(makeIcosphere(0.1f, 3), 2000, 0.1f, 1);
}

TEST(MeshBvh, ClosestPointMatchesBruteForceOnRealHead)
{
    REQUIRE_SHARED_ASSET(planckPath());
    const TriangleMesh head = planckHead();
    ASSERT_FALSE(head.triangles.empty()) << planckPath();
    ASSERT_EQ(validateMesh(head), "");
    expectClosestMatchesBruteForce(head, 1000, 0.05f, 2);
    // Points right on the surface (the hard case for pruning: many boxes at distance ~0).
    const MeshBvh bvh(head);
    std::mt19937 rng(3);
    std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(head.triangleCount() - 1));
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 500; ++i) {
        SurfacePoint sp;
        sp.triangle = pick(rng);
        const float a = unit(rng), b = unit(rng);
        sp.barycentric = a + b > 1.0f ? glm::vec2(1.0f - a, 1.0f - b) : glm::vec2(a, b);
        const glm::vec3 p = pointOn(head, sp);
        EXPECT_LT(bvh.closestPoint(p).distance, 1e-6f);
    }
}

TEST(MeshBvh, RaycastMatchesBruteForce)
{
    for (const TriangleMesh& mesh : { makeIcosphere(0.1f, 3), planckHead() }) {
        if (mesh.triangles.empty())
            continue; // the head is optional; the sphere alone still covers the logic
        const MeshBvh bvh(mesh);
        const Aabb box = boundsOf(mesh);
        std::mt19937 rng(4);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::normal_distribution<float> gauss;
        int hits = 0;
        for (int i = 0; i < 2000; ++i) {
            // Origins inside and around the box, random directions (not unit length on purpose).
            const glm::vec3 o
                = box.min - 0.25f * box.size() + 1.5f * box.size() * glm::vec3(unit(rng), unit(rng), unit(rng));
            // Half the rays aim near the middle of the box so that plenty of them hit.
            glm::vec3 d = 0.7f * glm::vec3(gauss(rng), gauss(rng), gauss(rng));
            if (i % 2 == 0)
                d = box.center() + 0.2f * box.size() * glm::vec3(gauss(rng), gauss(rng), gauss(rng)) - o;
            const float maxT = i % 4 == 0 ? 0.1f : 10.0f;
            const std::optional<float> expected = bruteRaycast(mesh, o, d, maxT);
            const auto got = bvh.raycast(o, d, maxT);
            ASSERT_EQ(got.has_value(), expected.has_value()) << "ray " << i;
            if (!got)
                continue;
            ++hits;
            EXPECT_FLOAT_EQ(got->t, *expected);
            EXPECT_NEAR(glm::length(got->point - (o + got->t * d)), 0.0f, 1e-6f);
            EXPECT_NEAR(glm::length(pointOn(mesh, got->surface) - got->point), 0.0f, 1e-5f);
        }
        EXPECT_GT(hits, 500); // the test means nothing if nothing is hit
    }
}

TEST(MeshBvh, RaysAlongAxesAndFromInside)
{
    const TriangleMesh sphere = makeIcosphere(0.1f, 4);
    const MeshBvh bvh(sphere);
    // Axis-aligned directions have zero components: the slab test must not produce NaN.
    for (const glm::vec3& d : { glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 2) }) {
        const auto fromOutside = bvh.raycast(-0.5f * d / glm::length(d), d, 1.0f);
        ASSERT_TRUE(fromOutside);
        EXPECT_NEAR(fromOutside->t * glm::length(d), 0.5f - 0.1f, 1e-3f); // the facets sit inside the sphere by < 1 mm
        const auto fromCentre = bvh.raycast(glm::vec3(0.0f), d, 1.0f); // back faces count too
        ASSERT_TRUE(fromCentre);
        EXPECT_NEAR(fromCentre->t * glm::length(d), 0.1f, 1e-3f);
    }
    EXPECT_FALSE(bvh.raycast(glm::vec3(0.5f, 0, 0), glm::vec3(1, 0, 0), 10.0f)); // pointing away
    EXPECT_FALSE(bvh.raycast(glm::vec3(-0.5f, 0, 0), glm::vec3(1, 0, 0), 0.3f)); // too short
    EXPECT_FALSE(bvh.raycast(glm::vec3(0.0f), glm::vec3(0.0f), 1.0f)); // no direction
    EXPECT_FALSE(bvh.raycast(glm::vec3(NAN, 0, 0), glm::vec3(1, 0, 0), 1.0f));
}

TEST(MeshBvh, OwnsItsDataAndHandlesBadInput)
{
    MeshBvh bvh;
    EXPECT_TRUE(bvh.empty());
    EXPECT_TRUE(std::isinf(bvh.closestPoint(glm::vec3(0.0f)).distance));
    EXPECT_FALSE(bvh.raycast(glm::vec3(0.0f), glm::vec3(1, 0, 0), 1.0f));

    {
        auto mesh = std::make_unique<TriangleMesh>(makeIcosphere(0.1f, 2));
        // A NaN corner, an index out of range and a zero-area triangle: the first two are dropped.
        mesh->positions.push_back(glm::vec3(NAN));
        const auto nanIndex = static_cast<unsigned>(mesh->positions.size() - 1);
        mesh->triangles.push_back({ 0, 1, nanIndex });
        mesh->triangles.push_back({ 0, 1, 100000 });
        mesh->triangles.push_back({ 0, 0, 0 });
        bvh = MeshBvh(*mesh);
        EXPECT_EQ(bvh.triangleCount(), mesh->triangleCount() - 2);
    } // the mesh is gone; the BVH keeps working from its own copy
    const auto c = bvh.closestPoint(glm::vec3(0.3f, 0.0f, 0.0f));
    EXPECT_NEAR(c.distance, 0.2f, 1e-3f);
    EXPECT_TRUE(bvh.raycast(glm::vec3(0.3f, 0.0f, 0.0f), glm::vec3(-1, 0, 0), 1.0f));
    EXPECT_FALSE(bvh.closestPointWithin(glm::vec3(0.3f, 0.0f, 0.0f), 0.15f));
    const auto within = bvh.closestPointWithin(glm::vec3(0.3f, 0.0f, 0.0f), 0.25f);
    ASSERT_TRUE(within);
    EXPECT_FLOAT_EQ(within->distance, c.distance);
    EXPECT_TRUE(std::isinf(bvh.closestPoint(glm::vec3(NAN)).distance));

    // Every triangle on one spot: the build must split by count instead of recursing forever.
    TriangleMesh pile;
    pile.positions = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
    pile.triangles.assign(1000, glm::uvec3(0, 1, 2));
    const MeshBvh pileBvh(pile);
    EXPECT_NEAR(pileBvh.closestPoint(glm::vec3(0.2f, 0.2f, 1.0f)).distance, 1.0f, 1e-6f);
}

// A head flat to a subnormal thickness (y is 0 or 1e-39 m): the binning's kBins / extent is
// infinite on that axis, and its bin index was a cast of NaN to int, which wrote far outside the
// bins (found by fuzz/fuzz_mesh). The tree must build and answer like brute force.
TEST(MeshBvh, BuildsOnASubnormalThickness)
{
    const float thin = 1e-39f;
    ASSERT_EQ(std::fpclassify(thin), FP_SUBNORMAL);
    TriangleMesh mesh;
    // An n x n grid of quads in the xz plane, a few corners raised by `thin`: the triangles'
    // centroids then differ in y by a subnormal amount.
    const int n = 6;
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k <= n; ++k)
            mesh.positions.push_back({ 0.05f * static_cast<float>(i), i % 3 == 0 && k % 2 == 0 ? thin : 0.0f,
                0.05f * static_cast<float>(k) });
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
            const auto v = static_cast<unsigned>(i * (n + 1) + k);
            mesh.triangles.push_back({ v, v + 1, v + n + 1 });
            mesh.triangles.push_back({ v + 1, v + n + 2, v + n + 1 });
        }
    const MeshBvh bvh(mesh);
    ASSERT_EQ(bvh.triangleCount(), mesh.triangleCount());
    for (const glm::vec3& p :
        { glm::vec3(0.12f, 0.1f, 0.07f), glm::vec3(-0.1f, -0.2f, 0.31f), glm::vec3(0.3f, 0.0f, 0.3f) })
        EXPECT_NEAR(bvh.closestPoint(p).distance, bruteClosest(mesh, p).distance, 1e-6f) << p.x << " " << p.z;
    const auto hit = bvh.raycast(glm::vec3(0.17f, 1.0f, 0.22f), glm::vec3(0.0f, -1.0f, 0.0f), 2.0f);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1.0f, 1e-6f);
}

// A ~330k-triangle mesh: rays from inside hit it, closest points come back. Its build and query
// times are figures in tests/bench (wisp_benchmarks), not assertions here.
TEST(MeshBvh, LargeMeshQueriesAnswer)
{
    const TriangleMesh sphere = makeIcosphere(0.12f, 7); // 327,680 triangles
    const MeshBvh bvh(sphere);

    std::mt19937 rng(5);
    std::normal_distribution<float> gauss;
    constexpr int kRays = 20000;
    int hits = 0;
    for (int i = 0; i < kRays; ++i) {
        const glm::vec3 d = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)) + glm::vec3(1e-6f));
        hits += bvh.raycast(-0.5f * d + 0.05f * glm::vec3(gauss(rng), gauss(rng), gauss(rng)), d, 1.0f).has_value();
    }
    float sum = 0.0f;
    for (int i = 0; i < kRays; ++i) { // within a few centimetres of the surface, where grooming asks
        const glm::vec3 d = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)) + glm::vec3(1e-6f));
        sum += bvh.closestPoint((0.12f + 0.01f * gauss(rng)) * d).distance;
    }
    EXPECT_GT(hits, kRays * 9 / 10);
    EXPECT_GT(sum, 0.0f);
}

// A nearly flat mesh whose triangle centroids span a subnormal, non-zero extent in z: kBins /
// extent was inf there, (c - lo) * inf NaN, and int(NaN) indexed bins[INT_MIN] (SIGSEGV on
// File > Open Head and wisp-cli). The BVH must build and answer like brute force.
TEST(MeshBvh, SubnormalCentroidExtentBuildsAndAnswers)
{
    TriangleMesh flat;
    constexpr int n = 20;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            flat.positions.push_back(
                { 0.01f * static_cast<float>(i), 0.01f * static_cast<float>(j), i == n - 1 ? 1e-42f : 0.0f });
    for (std::uint32_t i = 0; i + 1 < n; ++i)
        for (std::uint32_t j = 0; j + 1 < n; ++j) {
            const std::uint32_t a = i * n + j, b = a + 1, c = a + n, d = c + 1;
            flat.triangles.push_back({ a, b, d });
            flat.triangles.push_back({ a, d, c });
        }
    ASSERT_GT(boundsOf(flat).size().z, 0.0f);
    ASSERT_TRUE(std::isinf(16.0f / (0.5f * 1e-42f))); // the case the old binning could not take
    expectClosestMatchesBruteForce(flat, 200, 0.05f, 3);
    // Finite coordinates whose extent overflows to inf (-3e38 .. 3e38): the build still ends.
    TriangleMesh wide = flat;
    for (glm::vec3& p : wide.positions)
        p = glm::vec3((p.x / 0.095f - 1.0f) * 3e38f, (p.y / 0.095f - 1.0f) * 3e38f, p.z);
    ASSERT_TRUE(std::isinf(boundsOf(wide).size().x));
    const MeshBvh bvh(wide);
    EXPECT_FALSE(bvh.empty());
}

} // namespace
} // namespace wisp
