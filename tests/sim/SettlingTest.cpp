// Hair that settles, whatever the time step, and drawn strands (members included) that keep their
// length and stay out of the head: the figures of issue 11, asserted on real numbers. Inside is
// judged against the mesh itself (nearest triangle through a BVH), never the solver's own field.
#include "MeshFixtures.h"
#include "SimFixtures.h"

#include "sim/geometry/MeshBvh.h"
#include "sim/geometry/SignedDistanceField.h"
#include "sim/groom/GrowthMap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

using namespace wisp;
using namespace wisp::test;

namespace {

ParameterValues still(std::initializer_list<std::pair<Param, double>> changes)
{
    ParameterValues v = testParameters(); // no wind, no turbulence, a light groom
    for (const auto& [id, value] : changes)
        EXPECT_EQ(v.set(id, value), "") << parameterInfo(id).key;
    return v;
}

// Share of simulated tips that moved more than `metres` in one step.
double shareStillMoving(HairSimulation& sim, float metres)
{
    const std::vector<glm::vec3> before = simulatedTips(sim);
    sim.step();
    const std::vector<glm::vec3> after = simulatedTips(sim);
    std::size_t moving = 0;
    for (std::size_t i = 0; i < before.size(); ++i)
        moving += glm::distance(before[i], after[i]) > metres ? 1 : 0;
    return static_cast<double>(moving) / static_cast<double>(std::max<std::size_t>(before.size(), 1));
}

// Inside the mesh by ray parity, the majority of three rays across the head (an open mesh, such
// as a bust cut at the neck, has no inside below its cut; rays across still see its walls).
bool insideMesh(const MeshBvh& bvh, const glm::vec3& p)
{
    int votes = 0;
    for (const glm::vec3& direction : { glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), glm::vec3(-0.6f, 0.0f, -0.8f) }) {
        int crossings = 0;
        glm::vec3 origin = p;
        for (int guard = 0; guard < 64; ++guard) {
            const std::optional<MeshBvh::RayHit> hit = bvh.raycast(origin, direction, 10.0f);
            if (!hit)
                break;
            ++crossings;
            origin = hit->point + direction * 1e-5f;
        }
        votes += crossings % 2;
    }
    return votes >= 2;
}

struct DrawnMeasure {
    double worstStretch = 0.0; // largest |length / rest length - 1| of any drawn segment
    double deepestMetres = 0.0; // deepest drawn particle inside the head mesh
    bool worstIsKey = false;
    std::size_t strands = 0;
};

DrawnMeasure measureDrawn(const HairSimulation& sim, const MeshBvh& bvh)
{
    HairCurves frame;
    sim.buildFrame(frame);
    const HairCurves& rest = sim.groom().rest;
    DrawnMeasure m;
    m.strands = frame.strandCount();
    for (std::size_t s = 0; s < frame.strandCount(); ++s)
        for (std::uint32_t j = frame.offsets[s] + 1; j < frame.offsets[s + 1]; ++j) {
            const double restLength = glm::distance(rest.positions[j], rest.positions[j - 1]);
            const double now = glm::distance(frame.positions[j], frame.positions[j - 1]);
            const double stretch = std::abs(now / restLength - 1.0);
            if (stretch > m.worstStretch) {
                m.worstStretch = stretch;
                m.worstIsKey = sim.groom().isKey(s);
            }
        }
    for (const glm::vec3& x : frame.positions)
        if (insideMesh(bvh, x))
            m.deepestMetres = std::max(m.deepestMetres, static_cast<double>(bvh.closestPoint(x).distance));
    return m;
}

// Max Planck's head placed as the editor places it: millimetres to metres, box centred, and turned
// half a turn about +Y so that the face, toward -Z in the file, looks toward +Z.
TriangleMesh placedPlanck()
{
    TriangleMesh mesh;
    if (!std::filesystem::exists(planckPath()))
        return mesh;
    mesh = readObj(planckPath(), 0.001f);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    for (glm::vec3& p : mesh.positions) {
        p -= 0.5f * (lo + hi);
        p = glm::vec3(-p.x, p.y, -p.z);
    }
    return mesh;
}

} // namespace

TEST(Settling, TipsAgreeAcrossSubstepCounts)
{
    // The same hair settled with 1, 2, 4 and 8 substeps per step comes to the same shape: a
    // stiffness means the same at any substep count.
    std::vector<std::vector<glm::vec3>> tips;
    for (int substeps : { 1, 2, 4, 8 }) {
        auto sim = makeSimulation(still({ { Param::Substeps, substeps } }));
        run(*sim, 600);
        tips.push_back(simulatedTips(*sim));
    }
    for (std::size_t k = 0; k + 1 < tips.size(); ++k) {
        ASSERT_EQ(tips[k].size(), tips.back().size());
        double sum = 0.0;
        for (std::size_t i = 0; i < tips[k].size(); ++i)
            sum += glm::distance(tips[k][i], tips.back()[i]);
        const double mean = sum / static_cast<double>(tips[k].size());
        std::printf("figure: tips with %d substeps vs 8, mean distance %.2f mm\n", 1 << k, mean * 1000.0);
        EXPECT_LT(mean, 0.003) << "substeps " << (1 << k) << " vs 8: tips " << mean * 1000 << " mm apart on average";
    }
}

struct SettleCase {
    int substeps;
    int segments;
    bool curly;
};

class SettlingCases : public testing::TestWithParam<SettleCase> { };

TEST_P(SettlingCases, FewerThanOnePercentOfTipsStillMoveAfterTenSeconds)
{
    const SettleCase c = GetParam();
    ParameterValues v = still({ { Param::Substeps, c.substeps }, { Param::Segments, c.segments } });
    if (c.curly) {
        v.set(Param::CurlRadius, 0.008);
        v.set(Param::CurlTurns, 25.0);
    }
    auto sim = makeSimulation(v);
    run(*sim, 600); // 10 s at 60 Hz
    const double moving = shareStillMoving(*sim, 0.001f);
    std::printf("figure: %s, %d substeps, %d segments: %.1f %% of tips still move > 1 mm a step after 10 s\n",
        c.curly ? "curly" : "straight", c.substeps, c.segments, moving * 100.0);
    EXPECT_LT(moving, 0.01);
}

INSTANTIATE_TEST_SUITE_P(SubstepsSegmentsCurl, SettlingCases,
    testing::Values(SettleCase{ 1, 8, false }, SettleCase{ 8, 8, false }, SettleCase{ 1, 40, false },
        SettleCase{ 8, 40, false }, SettleCase{ 2, 40, true }, SettleCase{ 1, 40, true }, SettleCase{ 8, 40, true },
        SettleCase{ 4, 15, false }));

struct DrawnCase {
    bool planck;
    float windSpeed; // m/s
    float windAzimuth; // degrees
    bool curly;
    // The bars of issue 11, for every case. Max Planck under 30 m/s side wind used to reach 16-30 %
    // and 1-5 mm: strands blown into the crevice by the ear, where turning onto the tangent plane
    // flips from wall to wall, were pushed out along the normal and stretched (now they turn
    // along the arc toward the parent's normal, which keeps the length).
    double maxStretch = 0.01;
    double maxDepthMetres = 0.001;
};

class DrawnStrands : public testing::TestWithParam<DrawnCase> { };

TEST_P(DrawnStrands, KeepTheirLengthAndStayOutOfTheHead)
{
    const DrawnCase c = GetParam();
    ParameterValues v
        = still({ { Param::WindSpeed, c.windSpeed }, { Param::WindAzimuth, c.windAzimuth }, { Param::Density, 4.0 } });
    if (c.curly) {
        v.set(Param::CurlRadius, 0.008);
        v.set(Param::CurlTurns, 25.0);
        v.set(Param::Segments, 40);
    }
    if (c.windSpeed > 0.0f)
        v.set(Param::Turbulence, 0.5);
    if (c.planck)
        REQUIRE_SHARED_ASSET(planckPath());
    TriangleMesh head = c.planck ? placedPlanck() : defaultHead().mesh;
    ASSERT_FALSE(head.triangles.empty());
    HairSimulation sim;
    const std::vector<float> weights = c.planck ? scalpGrowth(head) : defaultHead().growthWeights;
    ASSERT_EQ(sim.setup(head, weights, v), "");
    const MeshBvh bvh(head);
    DrawnMeasure worst;
    for (int k = 0; k < 8; ++k) { // while it moves, not only once settled
        run(sim, 30);
        const DrawnMeasure m = measureDrawn(sim, bvh);
        if (m.worstStretch > worst.worstStretch) {
            worst.worstStretch = m.worstStretch;
            worst.worstIsKey = m.worstIsKey;
        }
        worst.deepestMetres = std::max(worst.deepestMetres, m.deepestMetres);
        worst.strands = m.strands;
    }
    ASSERT_GT(worst.strands, sim.groom().wispCount()); // members are drawn, not only keys
    std::printf("figure: drawn strands, %s, %s%s: max stretch %.2f %%, deepest %.2f mm inside\n",
        c.planck ? "Max Planck" : "built-in head",
        c.windSpeed > 0.0f ? (c.windAzimuth == 0.0f ? "30 m/s wind toward +X" : "30 m/s wind toward -X") : "gravity",
        c.curly ? ", curly" : "", worst.worstStretch * 100.0, worst.deepestMetres * 1000.0);
    EXPECT_LE(worst.worstStretch, c.maxStretch) << (worst.worstIsKey ? "a key hair" : "a member");
    EXPECT_LE(worst.deepestMetres, c.maxDepthMetres);
}

INSTANTIATE_TEST_SUITE_P(HeadsAndWinds, DrawnStrands,
    testing::Values(DrawnCase{ false, 0.0f, 0.0f, false }, DrawnCase{ false, 30.0f, 0.0f, false },
        DrawnCase{ false, 30.0f, 180.0f, false }, DrawnCase{ false, 0.0f, 0.0f, true },
        DrawnCase{ true, 0.0f, 0.0f, false }, DrawnCase{ true, 30.0f, 0.0f, false },
        DrawnCase{ true, 30.0f, 180.0f, false }, DrawnCase{ false, 30.0f, 0.0f, true }));

TEST(Stability, StrongDragAtTheLongestTimeStepDoesNotGainEnergy)
{
    // Drag 50/s at a 0.0999 s step with one substep (k dt ≈ 5) used to blow up; implicit drag
    // only ever takes velocity toward the wind's.
    ParameterValues v = still({ { Param::Drag, 50.0 }, { Param::TimeStep, 0.0999 }, { Param::Substeps, 1 } });
    auto sim = makeSimulation(v);
    // Energy per unit mass, summed over particles: kinetic + gravitational (y up).
    const double dt = v.getFloat(Param::TimeStep);
    std::vector<glm::vec3> p0, p1;
    auto energy = [&] {
        double e = 0.0;
        for (std::size_t i = 0; i < p0.size(); ++i) {
            EXPECT_TRUE(std::isfinite(p1[i].x) && std::isfinite(p1[i].y) && std::isfinite(p1[i].z));
            const glm::vec3 velocity = (p1[i] - p0[i]) / static_cast<float>(dt);
            e += 0.5 * glm::dot(velocity, velocity) + 9.81 * p1[i].y;
        }
        return e;
    };
    sim->copySimulated(p0);
    sim->step();
    sim->copySimulated(p1);
    const double first = energy();
    double last = first, kinetic = 0.0;
    for (int k = 0; k < 60; ++k) {
        p0 = p1;
        sim->step();
        sim->copySimulated(p1);
        last = energy();
        kinetic = 0.0;
        for (std::size_t i = 0; i < p0.size(); ++i)
            kinetic += 0.5 * glm::dot(p1[i] - p0[i], p1[i] - p0[i]) / (dt * dt);
    }
    EXPECT_LE(last, first);
    EXPECT_LT(kinetic / static_cast<double>(p1.size()), 1e-4); // at rest: below (1.4 cm/s)² / 2 a particle
    EXPECT_EQ(sim->solver().strandsReset(), 0u);
}

TEST(DrawnStrandsOnTheBody, NoDrawnParticleEndsInsideTheNeckOrShoulders)
{
    // Long hair reaches the shoulders: every drawn strand, members included, stays out of them.
    ParameterValues v = still({ { Param::Length, 0.5 }, { Param::Density, 3.0 }, { Param::Segments, 20 } });
    ASSERT_EQ(v.set(Param::Body, 1), "");
    HairSimulation sim;
    ASSERT_EQ(sim.setup(defaultHead().mesh, defaultHead().growthWeights, v), "");
    ASSERT_FALSE(sim.body().empty());
    run(sim, 300);
    HairCurves frame;
    sim.buildFrame(frame);
    double deepest = 0.0;
    std::size_t near = 0;
    for (const glm::vec3& p : frame.positions)
        for (const Capsule& c : sim.body()) {
            const glm::vec3 ab = c.b - c.a;
            const float t = std::clamp(glm::dot(p - c.a, ab) / std::max(glm::dot(ab, ab), 1e-12f), 0.0f, 1.0f);
            const double depth = c.radiusMetres - glm::distance(p, c.a + ab * t);
            deepest = std::max(deepest, depth);
            near += depth > -0.01 ? 1 : 0;
        }
    EXPECT_GT(near, 50u) << "the hair did not reach the body: the test proves nothing";
    std::printf("figure: drawn strands on the body (0.5 m hair), deepest %.2f mm inside a capsule\n", deepest * 1000.0);
    EXPECT_LT(deepest, 0.001);
}
