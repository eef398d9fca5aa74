#include "sim/geometry/SignedDistanceField.h"
#include "MeshFixtures.h"
#include "sim/geometry/MeshBvh.h"
#include "sim/geometry/SdfBake.h"
#include "sim/geometry/TriangleMesh.h"
#include "sim/util/ThreadPool.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <new>
#include <random>

namespace wisp {
namespace {

constexpr float kSqrt3 = 1.7320508f;

using test::makeIcosphere;
using test::planckPath;
using test::readObj;

// The exact generalized winding number: the sum of the triangles' signed solid angles over 4 pi
// (Van Oosterom and Strackee's formula), in double precision. The reference for the SDF's sign.
double windingNumber(const TriangleMesh& mesh, const glm::vec3& p)
{
    double sum = 0.0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 a = glm::dvec3(mesh.positions[t.x] - p), b = glm::dvec3(mesh.positions[t.y] - p),
                         c = glm::dvec3(mesh.positions[t.z] - p);
        const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        const double num = glm::dot(a, glm::cross(b, c));
        const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
        sum += 2.0 * std::atan2(num, den);
    }
    return sum / (4.0 * M_PI);
}

glm::vec3 samplePosition(const SignedDistanceField& f, int i, int j, int k)
{
    return f.origin() + glm::vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) * f.cellSize();
}

// Checks every sample of the field against the BVH's exact distances: exact in the band, a lower
// bound no more than sqrt(3) cells short outside it. Returns the number of band samples.
int expectExactBandAndBoundedFarField(const TriangleMesh& mesh, const SignedDistanceField& field)
{
    const MeshBvh bvh(mesh);
    const float h = field.cellSize();
    const float band = SignedDistanceField::kBandCells * h;
    const glm::ivec3 n = field.dims();
    int bandSamples = 0, failures = 0;
    for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i) {
                const float exact = bvh.closestPoint(samplePosition(field, i, j, k)).distance;
                const float value = std::abs(field.sample(i, j, k));
                if (exact <= band * 0.999f) {
                    ++bandSamples;
                    if (std::abs(value - exact) > 1e-6f + 1e-5f * exact && ++failures < 10)
                        ADD_FAILURE() << "band sample " << i << "," << j << "," << k << ": " << value << " vs "
                                      << exact;
                } else if (exact > band * 1.001f) {
                    if ((value > exact + 1e-6f || value < exact - kSqrt3 * h - 1e-6f || value < band * 0.999f)
                        && ++failures < 10)
                        ADD_FAILURE() << "far sample " << i << "," << j << "," << k << ": " << value << " vs " << exact;
                }
            }
    EXPECT_EQ(failures, 0);
    return bandSamples;
}

TEST(SignedDistanceField, SphereMatchesAnalyticDistance)
{
    const float radius = 0.1f, h = 0.005f;
    const TriangleMesh sphere = makeIcosphere(radius, 4); // facets sit < 0.1 mm inside the sphere
    std::string error;
    const SignedDistanceField field = SignedDistanceField::bake(sphere, h, 0.02f, &error);
    ASSERT_FALSE(field.empty()) << error;
    EXPECT_EQ(error, "");
    EXPECT_FLOAT_EQ(field.cellSize(), h);
    EXPECT_LE(field.origin().x, -radius - 0.02f + 1e-6f);
    EXPECT_GE(field.origin().x + (field.dims().x - 1) * h, radius + 0.02f - 1e-6f);

    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    auto randomDirection = [&] {
        for (;;) {
            const glm::vec3 d(unit(rng), unit(rng), unit(rng));
            const float l = glm::length(d);
            if (l > 0.1f && l <= 1.0f)
                return d / l;
        }
    };
    for (int s = 0; s < 2000; ++s) {
        const glm::vec3 dir = randomDirection();
        // Near the surface: within half a cell of the analytic value, gradient radial.
        const float r = radius + 0.015f * unit(rng);
        const glm::vec3 p = r * dir;
        const float d = field.distance(p);
        ASSERT_NEAR(d, r - radius, 0.5f * h) << "at radius " << r;
        EXPECT_GT(glm::dot(field.gradient(p), dir), 0.95f) << "at radius " << r;
        EXPECT_NEAR(glm::length(field.gradient(p)), 1.0f, 1e-5f);
        // Signs away from the surface.
        EXPECT_LT(field.distance((radius - 0.01f - 0.08f * std::abs(unit(rng))) * dir), 0.0f);
        EXPECT_GT(field.distance((radius + 0.01f + 0.05f * std::abs(unit(rng))) * dir), 0.0f);
    }
    // Deep inside the far field is a lower bound on |d|: within sqrt(3) cells (+ trilinear error).
    EXPECT_LE(field.distance(glm::vec3(0.0f)), -radius + kSqrt3 * h + 0.5f * h);
    EXPECT_GE(field.distance(glm::vec3(0.0f)), -radius - 1e-4f);

    const int band = expectExactBandAndBoundedFarField(sphere, field);
    EXPECT_GT(band, 5000);
}

TEST(SignedDistanceField, FarFieldGrowsMonotonically)
{
    const SignedDistanceField field = SignedDistanceField::bake(makeIcosphere(0.1f, 3), 0.004f, 0.06f);
    ASSERT_FALSE(field.empty());
    for (const glm::vec3& dir :
        { glm::vec3(1, 0, 0), glm::normalize(glm::vec3(1, 1, 1)), glm::normalize(glm::vec3(-0.3f, 0.2f, -1)) }) {
        float previous = field.distance(glm::vec3(0.0f));
        for (float r = 0.0f; r < 0.5f; r += 0.001f) { // out past the grid (0.16 m) too
            const float d = field.distance(r * dir);
            EXPECT_GE(d, previous - 1e-6f) << "at radius " << r;
            previous = d;
        }
        EXPECT_GT(previous, 0.3f); // outside the grid the value keeps growing with the distance to the box
        EXPECT_TRUE(std::isfinite(glm::length(field.gradient(0.5f * dir))));
        EXPECT_GT(glm::dot(field.gradient(0.5f * dir), dir), 0.5f);
    }
}

// A sphere with a cap of triangles cut away (an open neck, on a small scale): inside stays
// inside, including right under the hole; outside stays outside, including above it.
TEST(SignedDistanceField, OpenMeshKeepsItsInside)
{
    TriangleMesh open = makeIcosphere(0.1f, 3);
    std::vector<glm::uvec3> kept;
    for (const glm::uvec3& t : open.triangles) {
        const float y = (open.positions[t.x].y + open.positions[t.y].y + open.positions[t.z].y) / 3.0f;
        if (y < 0.07f) // the hole is about 0.14 m across
            kept.push_back(t);
    }
    ASSERT_LT(kept.size(), open.triangles.size());
    open.triangles = kept;
    std::string error;
    const SignedDistanceField field = SignedDistanceField::bake(open, 0.005f, 0.03f, &error);
    ASSERT_FALSE(field.empty()) << error;
    for (const glm::vec3& p : { glm::vec3(0.0f), glm::vec3(0, -0.05f, 0), glm::vec3(0.05f, 0, 0),
             glm::vec3(0, 0, -0.06f), glm::vec3(0, 0.04f, 0), glm::vec3(0.03f, 0.05f, 0.0f), glm::vec3(0, -0.09f, 0) })
        EXPECT_LT(field.distance(p), 0.0f) << p.x << "," << p.y << "," << p.z;
    for (const glm::vec3& p : { glm::vec3(0, 0.12f, 0), glm::vec3(0.0f, 0.11f, 0.05f), glm::vec3(0.12f, 0, 0),
             glm::vec3(0, -0.12f, 0), glm::vec3(0.08f, 0.08f, 0.08f) })
        EXPECT_GT(field.distance(p), 0.0f) << p.x << "," << p.y << "," << p.z;
    // Distances stay exact near the remaining surface.
    EXPECT_NEAR(field.distance(glm::vec3(0, -0.105f, 0)), 0.005f, 0.0015f);
    EXPECT_NEAR(field.distance(glm::vec3(0.095f, 0, 0)), -0.005f, 0.0015f);
}

// Two overlapping shells (an eyeball sunk into a head): the overlap and both shells are inside.
TEST(SignedDistanceField, OverlappingShellsAreInside)
{
    TriangleMesh mesh = makeIcosphere(0.1f, 3);
    const TriangleMesh eye = makeIcosphere(0.03f, 2);
    const auto base = static_cast<unsigned>(mesh.positions.size());
    for (const glm::vec3& p : eye.positions)
        mesh.positions.push_back(p + glm::vec3(0.09f, 0, 0));
    for (const glm::uvec3& t : eye.triangles)
        mesh.triangles.push_back(t + glm::uvec3(base));
    const SignedDistanceField field = SignedDistanceField::bake(mesh, 0.004f, 0.02f);
    ASSERT_FALSE(field.empty());
    EXPECT_LT(field.distance(glm::vec3(0.075f, 0, 0)), 0.0f); // in both
    EXPECT_LT(field.distance(glm::vec3(0.05f, 0, 0)), 0.0f); // in the head only
    EXPECT_LT(field.distance(glm::vec3(0.11f, 0, 0)), 0.0f); // in the eye only
    EXPECT_GT(field.distance(glm::vec3(0.13f, 0, 0)), 0.0f);
}

// A mesh whose triangles all face inward still has its inside negative.
TEST(SignedDistanceField, InwardFacingMeshStillHasItsInsideNegative)
{
    TriangleMesh mesh = makeIcosphere(0.1f, 3);
    for (glm::uvec3& t : mesh.triangles)
        std::swap(t.y, t.z);
    const SignedDistanceField field = SignedDistanceField::bake(mesh, 0.005f, 0.02f);
    ASSERT_FALSE(field.empty());
    EXPECT_LT(field.distance(glm::vec3(0.0f)), -0.08f);
    EXPECT_GT(field.distance(glm::vec3(0.115f, 0, 0)), 0.01f);
}

// An axis-aligned box whose faces, edges and corners lie exactly on grid lines: the crossing
// count must count rays through shared edges and vertices once.
TEST(SignedDistanceField, GridAlignedCubeHasExactSigns)
{
    TriangleMesh cube;
    const float s = 0.05f;
    cube.positions = { { -s, -s, -s }, { s, -s, -s }, { s, s, -s }, { -s, s, -s }, { -s, -s, s }, { s, -s, s },
        { s, s, s }, { -s, s, s } };
    cube.triangles = { { 0, 2, 1 }, { 0, 3, 2 }, { 4, 5, 6 }, { 4, 6, 7 }, { 0, 1, 5 }, { 0, 5, 4 }, { 2, 3, 7 },
        { 2, 7, 6 }, { 1, 2, 6 }, { 1, 6, 5 }, { 0, 4, 7 }, { 0, 7, 3 } };
    const float h = 0.01f; // the faces sit on sample planes
    const SignedDistanceField field = SignedDistanceField::bake(cube, h, 0.03f);
    ASSERT_FALSE(field.empty());
    const glm::ivec3 n = field.dims();
    for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i) {
                const glm::vec3 p = samplePosition(field, i, j, k);
                const glm::vec3 q = glm::abs(p);
                const float m = std::max(q.x, std::max(q.y, q.z));
                if (std::abs(m - s) < 1e-4f)
                    continue; // on the surface: either sign is right
                const bool inside = m < s;
                ASSERT_EQ(field.sample(i, j, k) < 0.0f, inside) << p.x << "," << p.y << "," << p.z;
            }
    // Two cells from a face: in the band, exact. The centre is five cells in: far field, a lower bound.
    EXPECT_NEAR(field.distance(glm::vec3(0.07f, 0.0f, 0.0f)), 0.02f, 1e-6f);
    EXPECT_NEAR(field.distance(glm::vec3(0.0f, 0.0f, 0.03f)), -0.02f, 1e-6f);
    EXPECT_LE(field.distance(glm::vec3(0.0f)), -s + kSqrt3 * h);
    EXPECT_GE(field.distance(glm::vec3(0.0f)), -s);
    expectExactBandAndBoundedFarField(cube, field);
}

TEST(SignedDistanceField, RealHeadSignsMatchExactWindingNumber)
{
    REQUIRE_SHARED_ASSET(planckPath());
    const TriangleMesh head = readObj(planckPath(), 0.001f);
    ASSERT_EQ(validateMesh(head), "");
    std::string error;
    const SignedDistanceField field = SignedDistanceField::bake(head, 0.004f, 0.02f, &error);
    ASSERT_FALSE(field.empty()) << error;

    std::mt19937 rng(11);
    const glm::ivec3 n = field.dims();
    std::uniform_int_distribution<int> ui(0, n.x - 1), uj(0, n.y - 1), uk(0, n.z - 1);
    int inside = 0;
    for (int s = 0; s < 400; ++s) {
        const int i = ui(rng), j = uj(rng), k = uk(rng);
        const float value = field.sample(i, j, k);
        if (std::abs(value) < 1e-4f)
            continue;
        const double w = windingNumber(head, samplePosition(field, i, j, k));
        EXPECT_EQ(value<0.0f, w> 0.5) << "sample " << i << "," << j << "," << k << " value " << value << " winding "
                                      << w;
        inside += value < 0.0f;
    }
    EXPECT_GT(inside, 10);
    EXPECT_GT(expectExactBandAndBoundedFarField(head, field), 10000);
}

TEST(SignedDistanceField, SameResultWithAnyThreadCount)
{
    const TriangleMesh sphere = makeIcosphere(0.1f, 3);
    const SignedDistanceField one = SignedDistanceField::bake(sphere, 0.004f, 0.02f, nullptr, 1);
    const SignedDistanceField three = SignedDistanceField::bake(sphere, 0.004f, 0.02f, nullptr, 3);
    const SignedDistanceField all = SignedDistanceField::bake(sphere, 0.004f, 0.02f);
    ASSERT_FALSE(one.empty());
    ASSERT_EQ(one.dims(), three.dims());
    ASSERT_EQ(one.dims(), all.dims());
    const std::size_t bytes = sizeof(float) * static_cast<std::size_t>(one.dims().x) * one.dims().y * one.dims().z;
    EXPECT_EQ(std::memcmp(one.data(), three.data(), bytes), 0);
    EXPECT_EQ(std::memcmp(one.data(), all.data(), bytes), 0);
}

// The bake runs on a pool it is given (HairSimulation gives it its solver's): the same bits as on
// the calling thread alone, and the same again when the pool is used a second time.
TEST(SignedDistanceField, BakeOnAGivenPoolIsBitIdenticalToOneThread)
{
    REQUIRE_SHARED_ASSET(planckPath());
    const TriangleMesh head = readObj(planckPath(), 0.001f);
    const float cell = 0.004f, margin = 0.02f;
    std::string error;
    const SignedDistanceField alone = SignedDistanceField::bake(head, cell, margin, &error, nullptr);
    ASSERT_FALSE(alone.empty()) << error;
    ThreadPool pool(4);
    ASSERT_EQ(pool.threadCount(), 4);
    for (int round = 0; round < 2; ++round) {
        const SignedDistanceField pooled = SignedDistanceField::bake(head, cell, margin, &error, &pool);
        ASSERT_FALSE(pooled.empty()) << error;
        ASSERT_EQ(pooled.dims(), alone.dims());
        const std::size_t bytes
            = sizeof(float) * static_cast<std::size_t>(alone.dims().x) * alone.dims().y * alone.dims().z;
        EXPECT_EQ(std::memcmp(alone.data(), pooled.data(), bytes), 0) << "round " << round;
    }
}

// The bake's loop over slabs on the pool: every index exactly once; a slab that runs out of memory
// makes it return false (the bake's "not enough memory" message) instead of throwing out of a
// pool thread, and the pool goes on working afterwards.
TEST(SignedDistanceField, SlabLoopOnThePoolVisitsEachSlabOnceAndTurnsBadAllocIntoFalse)
{
    ThreadPool pool(3);
    constexpr int kSlabs = 257;
    std::vector<std::atomic<int>> visits(kSlabs);
    EXPECT_TRUE(sdf_detail::parallelFor(&pool, kSlabs, [&](int i) { ++visits[static_cast<std::size_t>(i)]; }));
    for (int i = 0; i < kSlabs; ++i)
        EXPECT_EQ(visits[static_cast<std::size_t>(i)].load(), 1) << "slab " << i;

    std::atomic<int> ran{ 0 };
    EXPECT_FALSE(sdf_detail::parallelFor(&pool, kSlabs, [&](int i) {
        ++ran;
        if (i == 100)
            throw std::bad_alloc();
    }));
    EXPECT_GE(ran.load(), 1);
    EXPECT_FALSE(sdf_detail::parallelFor(nullptr, 5, [](int i) {
        if (i == 2)
            throw std::bad_alloc();
    }));

    std::atomic<int> after{ 0 };
    EXPECT_TRUE(sdf_detail::parallelFor(&pool, kSlabs, [&](int) { ++after; }));
    EXPECT_EQ(after.load(), kSlabs);
}

TEST(SignedDistanceField, BadInputGivesAnEmptyFieldAndAMessage)
{
    const TriangleMesh sphere = makeIcosphere(0.1f, 1);
    auto expectRejected = [](const TriangleMesh& mesh, float cell, float margin, const char* what) {
        std::string error;
        const SignedDistanceField f = SignedDistanceField::bake(mesh, cell, margin, &error);
        EXPECT_TRUE(f.empty()) << what;
        EXPECT_FALSE(error.empty()) << what;
        EXPECT_EQ(f.data(), nullptr) << what;
        EXPECT_EQ(f.dims(), glm::ivec3(0)) << what;
        std::printf("[ message  ] %s: %s\n", what, error.c_str());
    };
    expectRejected(TriangleMesh{}, 0.01f, 0.01f, "no triangles");
    TriangleMesh nan = sphere;
    nan.positions[3].y = NAN;
    expectRejected(nan, 0.01f, 0.01f, "NaN vertex");
    TriangleMesh outOfRange = sphere;
    outOfRange.triangles.push_back({ 0, 1, 1000 });
    expectRejected(outOfRange, 0.01f, 0.01f, "index out of range");
    TriangleMesh flat;
    flat.positions = { { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 } };
    flat.triangles = { { 0, 1, 2 } };
    expectRejected(flat, 0.01f, 0.01f, "zero area");
    expectRejected(sphere, 0.0f, 0.01f, "zero cell size");
    expectRejected(sphere, -0.01f, 0.01f, "negative cell size");
    expectRejected(sphere, NAN, 0.01f, "NaN cell size");
    expectRejected(sphere, INFINITY, 0.01f, "infinite cell size");
    expectRejected(sphere, 1e9f, 0.01f, "huge cell size");
    expectRejected(sphere, 0.01f, -1.0f, "negative margin");
    expectRejected(sphere, 0.01f, NAN, "NaN margin");
    expectRejected(sphere, 0.01f, 1e9f, "huge margin");
    TriangleMesh huge = sphere;
    for (glm::vec3& p : huge.positions)
        p *= 1e30f;
    expectRejected(huge, 0.01f, 0.01f, "huge mesh");
    // A mesh in millimetres read as metres (0.2 km across) still bakes: 10 km is the limit.
    TriangleMesh millimetres = sphere;
    for (glm::vec3& p : millimetres.positions)
        p *= 1000.0f;
    std::string error;
    const SignedDistanceField coarse = SignedDistanceField::bake(millimetres, 2.5f, 20.0f, &error);
    ASSERT_FALSE(coarse.empty()) << error;
    EXPECT_LE(static_cast<std::size_t>(coarse.dims().x) * coarse.dims().y * coarse.dims().z,
        SignedDistanceField::kMaxSamples);
    EXPECT_LT(coarse.distance(glm::vec3(0.0f)), -50.0f);

    // The empty field answers without crashing: nothing to collide with.
    const SignedDistanceField empty;
    EXPECT_TRUE(std::isinf(empty.distance(glm::vec3(0.0f))));
    EXPECT_EQ(empty.gradient(glm::vec3(0.0f)), glm::vec3(0, 1, 0));
}

// A tiny cell size asks for billions of samples: the grid is capped and the cell grows.
TEST(SignedDistanceField, HugeGridIsCappedByGrowingTheCell)
{
    std::string error;
    const SignedDistanceField field = SignedDistanceField::bake(makeIcosphere(0.1f, 2), 1e-6f, 0.02f, &error);
    ASSERT_FALSE(field.empty()) << error;
    const glm::ivec3 n = field.dims();
    EXPECT_LE(static_cast<std::size_t>(n.x) * n.y * n.z, SignedDistanceField::kMaxSamples);
    EXPECT_GT(static_cast<std::size_t>(n.x) * n.y * n.z, SignedDistanceField::kMaxSamples / 2);
    EXPECT_GT(field.cellSize(), 1e-6f);
    EXPECT_GE(field.origin().x + (n.x - 1) * field.cellSize(), 0.12f - 1e-6f); // still covers the box
    EXPECT_LT(field.distance(glm::vec3(0.0f)), -0.09f);
    EXPECT_NEAR(field.distance(glm::vec3(0.105f, 0, 0)), 0.005f, 0.001f);
}

// The solver's lookup table: each sample's distance and its outward unit normal, built once per
// field and shared by its copies (every solver colliding with a head reads the same table; a comb
// release no longer builds its own twice).
TEST(SignedDistanceField, SamplesWithNormalsAreOneSharedTableOfOutwardNormals)
{
    const float radius = 0.1f, h = 0.005f;
    const SignedDistanceField field = SignedDistanceField::bake(makeIcosphere(radius, 4), h, 0.02f);
    ASSERT_FALSE(field.empty());
    const std::vector<glm::vec4>& table = field.samplesWithNormals();
    const glm::ivec3 n = field.dims();
    ASSERT_EQ(table.size(), static_cast<std::size_t>(n.x) * n.y * n.z);
    const SignedDistanceField copy = field;
    EXPECT_EQ(copy.samplesWithNormals().data(), table.data());
    EXPECT_EQ(field.samplesWithNormals().data(), table.data());
    int nearSurface = 0;
    for (int k = 0; k < n.z; k += 3)
        for (int j = 0; j < n.y; j += 3)
            for (int i = 0; i < n.x; i += 3) {
                const glm::vec4 node = table[static_cast<std::size_t>(i)
                    + static_cast<std::size_t>(n.x) * (j + static_cast<std::size_t>(n.y) * k)];
                ASSERT_EQ(node.x, field.sample(i, j, k));
                const glm::vec3 normal(node.y, node.z, node.w);
                ASSERT_NEAR(glm::length(normal), 1.0f, 1e-5f);
                const glm::vec3 at = field.origin() + glm::vec3(i, j, k) * h;
                if (std::abs(glm::length(at) - radius) < 0.01f) {
                    ++nearSurface;
                    EXPECT_GT(glm::dot(normal, glm::normalize(at)), 0.95f)
                        << "at " << at.x << " " << at.y << " " << at.z;
                }
            }
    EXPECT_GT(nearSurface, 500);
    EXPECT_TRUE(SignedDistanceField{}.samplesWithNormals().empty());
}

TEST(SignedDistanceField, GradientIsNeverNaN)
{
    const SignedDistanceField field = SignedDistanceField::bake(makeIcosphere(0.1f, 2), 0.01f, 0.02f);
    ASSERT_FALSE(field.empty());
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 p = (i % 2 ? 0.15f : 3.0f) * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 g = field.gradient(p);
        ASSERT_NEAR(glm::length(g), 1.0f, 1e-4f);
    }
    for (const glm::vec3& p :
        { glm::vec3(0.0f), glm::vec3(NAN), glm::vec3(INFINITY, 0, 0), glm::vec3(1e30f), field.origin() }) {
        const glm::vec3 g = field.gradient(p);
        EXPECT_TRUE(std::isfinite(g.x) && std::isfinite(g.y) && std::isfinite(g.z));
        EXPECT_NEAR(glm::length(g), 1.0f, 1e-4f);
    }
}

} // namespace
} // namespace wisp
