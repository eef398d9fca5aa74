#include "sim/groom/ScalpBrush.h"
#include "MeshFixtures.h"
#include "sim/geometry/DefaultHead.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

namespace wisp {
namespace {

// Built once: every test reads the same head and brush.
const TriangleMesh& head()
{
    static const TriangleMesh mesh = makeDefaultHead().mesh;
    return mesh;
}
const ScalpBrush& brush()
{
    static const ScalpBrush b(head());
    return b;
}

std::uint32_t nearestVertex(const TriangleMesh& mesh, glm::vec3 to)
{
    std::uint32_t best = 0;
    for (std::uint32_t v = 1; v < mesh.positions.size(); ++v)
        if (glm::distance(mesh.positions[v], to) < glm::distance(mesh.positions[best], to))
            best = v;
    return best;
}

// A point on the scalp well off the mid-plane (the right side, above the ear), and its mirror image.
glm::vec3 sideCentre()
{
    static const glm::vec3 centre = head().positions[nearestVertex(head(), { 0.2f, 0.09f, -0.02f })];
    return centre;
}
glm::vec3 mirrorOf(glm::vec3 p)
{
    return { 2.0f * brush().mirrorPlaneX() - p.x, p.y, p.z };
}

// Distance from vertex v to the nearer of the dab's centres.
float nearestCentreDistance(std::uint32_t v, glm::vec3 centre, bool mirror)
{
    const glm::vec3 p = head().positions[v];
    const float d = glm::distance(p, centre);
    return mirror ? std::min(d, glm::distance(p, mirrorOf(centre))) : d;
}

bool sameBits(float a, float b)
{
    return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

std::vector<std::uint32_t> changedBetween(const std::vector<float>& before, const std::vector<float>& after)
{
    std::vector<std::uint32_t> changed;
    for (std::uint32_t v = 0; v < before.size(); ++v)
        if (!sameBits(before[v], after[v]))
            changed.push_back(v);
    return changed;
}

// Weights that differ from vertex to vertex, away from 0 and 1, so every mode has room to move.
std::vector<float> variedWeights(std::size_t n, float lo, float hi, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    std::vector<float> w(n);
    for (float& x : w)
        x = u(rng);
    return w;
}

TEST(ScalpBrush, MirrorPlaneIsTheHeadsCentre)
{
    EXPECT_FLOAT_EQ(brush().mirrorPlaneX(), boundsOf(head()).center().x);
    EXPECT_EQ(brush().vertexCount(), head().vertexCount());
    const glm::vec3 c = sideCentre();
    std::printf("[ value    ] side centre (%.4f, %.4f, %.4f) m, mirror plane x = %.6f m\n", c.x, c.y, c.z,
        brush().mirrorPlaneX());
}

TEST(ScalpBrush, AddRaisesWeightsInsideBothSpheresAndNowhereElse)
{
    const BrushSettings s{ .radiusMetres = 0.02f, .strength = 0.5f, .falloff = 0.5f, .mode = BrushMode::Add };
    const glm::vec3 centre = sideCentre();
    ASSERT_GT(centre.x - brush().mirrorPlaneX(), 2.0f * s.radiusMetres) << "the two spheres must not overlap here";

    const std::vector<float> before = variedWeights(head().vertexCount(), 0.1f, 0.9f, 1);
    std::vector<float> after = before;
    const std::vector<std::uint32_t> changed = brush().dab(centre, s, after);
    EXPECT_EQ(changed, changedBetween(before, after));

    int raisedRight = 0, raisedLeft = 0;
    for (std::uint32_t v = 0; v < before.size(); ++v) {
        const float d = nearestCentreDistance(v, centre, true);
        if (d > s.radiusMetres) {
            EXPECT_TRUE(sameBits(after[v], before[v])) << "vertex " << v << " at " << d << " m";
            continue;
        }
        const float influence = s.strength * brushFalloff(d / s.radiusMetres, s.falloff);
        const float expected = before[v] + influence * (1.0f - before[v]);
        EXPECT_NEAR(after[v], expected, 1e-6f) << "vertex " << v;
        if (d < 0.99f * s.radiusMetres) {
            EXPECT_GT(after[v], before[v]) << "vertex " << v;
            ++(head().positions[v].x > brush().mirrorPlaneX() ? raisedRight : raisedLeft);
        }
    }
    EXPECT_GT(raisedRight, 20);
    EXPECT_GT(raisedLeft, 20); // the mirrored dab
}

TEST(ScalpBrush, EraseLowersWeightsTowardZero)
{
    const BrushSettings s{ .radiusMetres = 0.02f, .strength = 0.5f, .falloff = 0.0f, .mode = BrushMode::Erase };
    const std::vector<float> before(head().vertexCount(), 0.8f);
    std::vector<float> after = before;
    const std::vector<std::uint32_t> changed = brush().dab(sideCentre(), s, after);
    EXPECT_EQ(changed, changedBetween(before, after));
    ASSERT_GT(changed.size(), 40u);
    for (std::uint32_t v = 0; v < before.size(); ++v) {
        if (nearestCentreDistance(v, sideCentre(), true) <= s.radiusMetres)
            EXPECT_FLOAT_EQ(after[v], 0.4f) << "vertex " << v;
        else
            EXPECT_TRUE(sameBits(after[v], before[v])) << "vertex " << v;
    }
    // Full strength clears to exactly 0, and more erasing changes nothing further.
    std::vector<float> cleared = before;
    brush().dab(sideCentre(), BrushSettings{ .strength = 1.0f, .falloff = 0.0f, .mode = BrushMode::Erase }, cleared);
    EXPECT_EQ(cleared[nearestVertex(head(), sideCentre())], 0.0f);
    std::vector<float> again = cleared;
    EXPECT_TRUE(
        brush()
            .dab(sideCentre(), BrushSettings{ .strength = 1.0f, .falloff = 0.0f, .mode = BrushMode::Erase }, again)
            .empty());
}

TEST(ScalpBrush, SmoothCalmsANoisyPatchAndLeavesTheRestAlone)
{
    const BrushSettings s{ .radiusMetres = 0.02f, .strength = 1.0f, .falloff = 0.5f, .mode = BrushMode::Smooth };
    const glm::vec3 centre = sideCentre();
    const std::vector<float> before = variedWeights(head().vertexCount(), 0.0f, 1.0f, 7);
    std::vector<float> after = before;
    const std::vector<std::uint32_t> changed = brush().dab(centre, s, after);
    EXPECT_EQ(changed, changedBetween(before, after));

    // Variance of the patch's inner half, where the brush is at full strength.
    auto variance = [&](const std::vector<float>& w) {
        double sum = 0.0, sum2 = 0.0;
        int n = 0;
        for (std::uint32_t v = 0; v < w.size(); ++v)
            if (glm::distance(head().positions[v], centre) < 0.5f * s.radiusMetres) {
                sum += w[v];
                sum2 += double(w[v]) * w[v];
                ++n;
            }
        EXPECT_GT(n, 10);
        return sum2 / n - (sum / n) * (sum / n);
    };
    const double varianceBefore = variance(before), varianceAfter = variance(after);
    std::printf("[ value    ] smooth: patch variance %.4f -> %.4f\n", varianceBefore, varianceAfter);
    EXPECT_LT(varianceAfter, 0.5 * varianceBefore);

    for (std::uint32_t v = 0; v < before.size(); ++v) {
        EXPECT_GE(after[v], 0.0f);
        EXPECT_LE(after[v], 1.0f);
        if (nearestCentreDistance(v, centre, true) > s.radiusMetres) {
            EXPECT_TRUE(sameBits(after[v], before[v])) << "vertex " << v;
        }
    }
    // A uniform mask is already smooth: nothing to change.
    std::vector<float> flat(head().vertexCount(), 0.6f);
    EXPECT_TRUE(brush().dab(centre, s, flat).empty());
}

TEST(ScalpBrush, HardEdgeChangesTheWholeDiskEqually)
{
    const BrushSettings s{ .radiusMetres = 0.02f, .strength = 0.3f, .falloff = 0.0f, .mirrorX = false };
    const glm::vec3 centre = sideCentre();
    std::vector<float> w(head().vertexCount(), 0.0f);
    const std::vector<std::uint32_t> changed = brush().dab(centre, s, w);
    EXPECT_EQ(changed, brush().verticesNear(centre, s.radiusMetres));
    ASSERT_GT(changed.size(), 40u);
    for (std::uint32_t v : changed)
        EXPECT_EQ(w[v], 0.3f) << "vertex " << v << " at " << glm::distance(head().positions[v], centre) << " m";
}

TEST(ScalpBrush, SmoothFalloffGivesLessAtTheRimThanAtTheCentre)
{
    const BrushSettings s{ .radiusMetres = 0.02f, .strength = 0.3f, .falloff = 1.0f, .mirrorX = false };
    const glm::vec3 centre = sideCentre(); // a vertex: distance 0 there
    std::vector<float> w(head().vertexCount(), 0.0f);
    brush().dab(centre, s, w);
    EXPECT_EQ(w[nearestVertex(head(), centre)], 0.3f);

    // The change never grows with distance, and the outer 15% gets less than 7% of the centre's
    // (1 - smoothstep(0.85) = 0.061).
    std::vector<std::pair<float, float>> byDistance; // (metres, weight)
    for (std::uint32_t v : brush().verticesNear(centre, s.radiusMetres))
        byDistance.emplace_back(glm::distance(head().positions[v], centre), w[v]);
    std::sort(byDistance.begin(), byDistance.end());
    int rim = 0;
    for (std::size_t i = 1; i < byDistance.size(); ++i) {
        EXPECT_LE(byDistance[i].second, byDistance[i - 1].second) << "at " << byDistance[i].first << " m";
        if (byDistance[i].first > 0.85f * s.radiusMetres) {
            EXPECT_LT(byDistance[i].second, 0.07f * 0.3f);
            ++rim;
        }
    }
    EXPECT_GT(rim, 5);
    EXPECT_EQ(brushFalloff(0.0f, 1.0f), 1.0f);
    EXPECT_EQ(brushFalloff(1.0f, 1.0f), 0.0f);
    EXPECT_FLOAT_EQ(brushFalloff(0.5f, 1.0f), 0.5f);
    EXPECT_EQ(brushFalloff(0.75f, 0.5f), 0.5f); // halfway through the outer half
    EXPECT_EQ(brushFalloff(1.0f, 0.0f), 1.0f);
    EXPECT_EQ(brushFalloff(1.01f, 0.0f), 0.0f);
}

TEST(ScalpBrush, FullStrengthAddReachesOneAtTheCentre)
{
    const glm::vec3 centre = sideCentre();
    std::vector<float> w = variedWeights(head().vertexCount(), 0.0f, 0.5f, 3);
    brush().dab(centre, BrushSettings{ .strength = 1.0f }, w);
    EXPECT_EQ(w[nearestVertex(head(), centre)], 1.0f);
    EXPECT_EQ(w[nearestVertex(head(), mirrorOf(centre))], 1.0f);
}

TEST(ScalpBrush, WithoutMirrorOnlyOneSideChanges)
{
    const BrushSettings s{ .radiusMetres = 0.03f, .mirrorX = false };
    const std::vector<float> before(head().vertexCount(), 0.0f);
    std::vector<float> after = before;
    const std::vector<std::uint32_t> changed = brush().dab(sideCentre(), s, after);
    EXPECT_EQ(changed, changedBetween(before, after));
    ASSERT_GT(changed.size(), 40u);
    for (std::uint32_t v : changed) {
        EXPECT_GT(head().positions[v].x, brush().mirrorPlaneX()) << "vertex " << v;
        EXPECT_LE(glm::distance(head().positions[v], sideCentre()), s.radiusMetres);
    }
}

TEST(ScalpBrush, OverlappingMirrorSpheresPaintOnce)
{
    // 5 mm off the mid-plane on the crown: the spheres' centres lie 1 cm apart, 2 cm radius each.
    const glm::vec3 centre = head().positions[nearestVertex(head(), { brush().mirrorPlaneX() + 0.005f, 0.2f, 0.0f })];
    const float offPlane = std::abs(centre.x - brush().mirrorPlaneX());
    ASSERT_GT(offPlane, 0.0005f);
    ASSERT_LT(offPlane, 0.008f);

    for (float falloff : { 0.0f, 1.0f }) {
        SCOPED_TRACE(falloff);
        const BrushSettings s{ .radiusMetres = 0.02f, .strength = 0.5f, .falloff = falloff };
        std::vector<float> w(head().vertexCount(), 0.0f);
        const std::vector<std::uint32_t> changed = brush().dab(centre, s, w);
        EXPECT_EQ(changed, changedBetween(std::vector<float>(w.size(), 0.0f), w));
        int inBoth = 0;
        for (std::uint32_t v = 0; v < w.size(); ++v) {
            const glm::vec3 p = head().positions[v];
            const float da = glm::distance(p, centre), db = glm::distance(p, mirrorOf(centre));
            inBoth += da <= s.radiusMetres && db <= s.radiusMetres;
            // One dab's worth with the nearer centre's influence; two dabs would give 0.75 at full influence.
            const float expected = s.strength * brushFalloff(std::min(da, db) / s.radiusMetres, falloff);
            EXPECT_NEAR(w[v], expected, 1e-6f) << "vertex " << v;
        }
        EXPECT_GT(inBoth, 40);
    }
}

TEST(ScalpBrush, InvalidInputChangesNothing)
{
    const std::vector<float> before = variedWeights(head().vertexCount(), 0.0f, 1.0f, 11);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();

    auto refused = [&](const glm::vec3& centre, const BrushSettings& s) {
        std::vector<float> w = before;
        const bool nothingReturned = brush().dab(centre, s, w).empty();
        return nothingReturned && changedBetween(before, w).empty();
    };
    EXPECT_TRUE(refused(sideCentre(), BrushSettings{ .radiusMetres = 0.0f }));
    EXPECT_TRUE(refused(sideCentre(), BrushSettings{ .radiusMetres = 0.6f }));
    EXPECT_TRUE(refused(sideCentre(), BrushSettings{ .radiusMetres = nan }));
    EXPECT_TRUE(refused(sideCentre(), BrushSettings{ .strength = nan }));
    EXPECT_TRUE(refused(sideCentre(), BrushSettings{ .strength = -0.1f }));
    EXPECT_TRUE(refused(sideCentre(), BrushSettings{ .falloff = 2.0f }));
    EXPECT_TRUE(refused(sideCentre(), BrushSettings{ .mode = static_cast<BrushMode>(7) }));
    EXPECT_TRUE(refused({ nan, 0.1f, 0.0f }, BrushSettings{}));
    EXPECT_TRUE(refused({ 0.0f, inf, 0.0f }, BrushSettings{}));
    EXPECT_TRUE(refused({ 5.0f, 5.0f, 5.0f }, BrushSettings{})); // far from the head: nothing within reach
    EXPECT_FALSE(refused(sideCentre(), BrushSettings{})); // the control: a valid dab does change something

    for (std::size_t size : { head().vertexCount() - 1, head().vertexCount() + 1, std::size_t(0) }) {
        std::vector<float> w(size, 0.5f);
        EXPECT_TRUE(brush().dab(sideCentre(), BrushSettings{}, w).empty()) << size;
        EXPECT_TRUE(std::all_of(w.begin(), w.end(), [](float x) { return x == 0.5f; }));
    }
    std::vector<float> none;
    EXPECT_TRUE(ScalpBrush().dab({ 0, 0, 0 }, BrushSettings{}, none).empty());

    EXPECT_EQ(validateBrush(BrushSettings{}), "");
    EXPECT_EQ(validateBrush(BrushSettings{ .radiusMetres = 0.0f }), "brush radius: 0 is outside 0.0005..0.5 m");
    EXPECT_EQ(validateBrush(BrushSettings{ .strength = nan }), "brush strength: nan is not a finite number");
    EXPECT_EQ(validateBrush(BrushSettings{ .strength = -nan }), "brush strength: nan is not a finite number");
    EXPECT_EQ(validateBrush(BrushSettings{ .falloff = 1.5f }), "brush falloff: 1.5 is outside 0..1");
    EXPECT_EQ(
        validateBrush(BrushSettings{ .mode = static_cast<BrushMode>(7) }), "brush mode: 7 is not add, erase or smooth");
}

TEST(ScalpBrush, NonFiniteWeightsAreRepairedWhereTheBrushTouches)
{
    std::vector<float> w(head().vertexCount(), 0.0f);
    const std::uint32_t v = nearestVertex(head(), sideCentre());
    w[v] = std::numeric_limits<float>::quiet_NaN();
    const std::vector<std::uint32_t> changed
        = brush().dab(sideCentre(), BrushSettings{ .strength = 0.25f, .falloff = 0.0f, .mode = BrushMode::Erase }, w);
    EXPECT_EQ(changed, std::vector<std::uint32_t>{ v }); // the others are 0 already
    EXPECT_EQ(w[v], 0.0f);
}

TEST(ScalpBrush, VerticesNearMatchesAScanOfAllVertices)
{
    const TriangleMesh sphere = test::makeIcosphere(0.1f, 4);
    const ScalpBrush sphereBrush(sphere);
    for (const TriangleMesh* meshPointer : { &sphere, &head() }) {
        const TriangleMesh& mesh = *meshPointer;
        const ScalpBrush& b = &mesh == &sphere ? sphereBrush : brush();
        std::mt19937 rng(5);
        for (int i = 0; i < 50; ++i) {
            const glm::vec3 centre = mesh.positions[rng() % mesh.positions.size()];
            const float radius = std::array{ 0.0f, 0.003f, 0.02f, 0.05f, 1.0f }[i % 5];
            std::vector<std::uint32_t> expected;
            for (std::uint32_t v = 0; v < mesh.positions.size(); ++v)
                if (glm::dot(mesh.positions[v] - centre, mesh.positions[v] - centre) <= radius * radius)
                    expected.push_back(v);
            ASSERT_EQ(b.verticesNear(centre, radius), expected) << "radius " << radius;
        }
    }
    EXPECT_TRUE(brush().verticesNear({ 0, 0, 0 }, -1.0f).empty());
}

TEST(ScalpBrush, MalformedMeshesAreSafe)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // A NaN vertex is never painted, and a triangle naming a missing vertex adds no neighbours.
    TriangleMesh sphere = test::makeIcosphere(0.1f, 3);
    sphere.positions[0] = { nan, 0.0f, 0.0f };
    sphere.triangles.push_back({ 1, 2, 999999 });
    const ScalpBrush sphereBrush(sphere);
    EXPECT_FLOAT_EQ(sphereBrush.mirrorPlaneX(), 0.0f);
    std::vector<float> w(sphere.vertexCount(), 0.0f);
    const glm::vec3 centre = sphere.positions[1];
    for (BrushMode mode : { BrushMode::Add, BrushMode::Smooth })
        sphereBrush.dab(centre, BrushSettings{ .radiusMetres = 0.5f, .mode = mode }, w);
    EXPECT_EQ(w[0], 0.0f);
    EXPECT_GT(w[1], 0.0f);

    // Coordinates far beyond a head (a mesh in millimetres): the grid coarsens instead of growing.
    const TriangleMesh big = test::makeIcosphere(100.0f, 3);
    const ScalpBrush bigBrush(big);
    std::vector<std::uint32_t> expected;
    for (std::uint32_t v = 0; v < big.positions.size(); ++v)
        if (glm::dot(big.positions[v] - big.positions[5], big.positions[v] - big.positions[5]) <= 0.25f)
            expected.push_back(v);
    EXPECT_EQ(bigBrush.verticesNear(big.positions[5], 0.5f), expected);

    // An extent that overflows float: nothing can be painted, and nothing breaks.
    TriangleMesh huge = sphere;
    huge.positions[0] = glm::vec3(3e38f);
    huge.positions[1] = glm::vec3(-3e38f);
    const ScalpBrush hugeBrush(huge);
    std::vector<float> hw(huge.vertexCount(), 0.0f);
    EXPECT_TRUE(hugeBrush.dab(huge.positions[2], BrushSettings{}, hw).empty());
    EXPECT_TRUE(hugeBrush.verticesNear(huge.positions[2], 1.0f).empty());
}

} // namespace
} // namespace wisp
