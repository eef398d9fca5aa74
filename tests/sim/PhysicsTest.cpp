// Tests that the solver's motion is the physics the papers describe, by numbers.
#include "SimFixtures.h"

#include "sim/geometry/MeshBvh.h"
#include "sim/geometry/SignedDistanceField.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace wisp;
using namespace wisp::test;

namespace {

// Largest relative deviation of any simulated segment from its rest length.
double worstStretch(const HairSimulation& sim)
{
    std::vector<glm::vec3> p;
    sim.copySimulated(p);
    const HairCurves rest = sim.simulatesAllStrands() ? sim.groom().rest : keyRestCurves(sim.groom());
    double worst = 0.0;
    for (std::size_t s = 0; s < rest.strandCount(); ++s)
        for (std::uint32_t j = rest.offsets[s] + 1; j < rest.offsets[s + 1]; ++j) {
            const double restLength = glm::distance(rest.positions[j], rest.positions[j - 1]);
            worst = std::max(worst, std::abs(glm::distance(p[j], p[j - 1]) - restLength) / restLength);
        }
    return worst;
}

bool allFinite(const HairSimulation& sim)
{
    std::vector<glm::vec3> p;
    sim.copySimulated(p);
    for (const glm::vec3& v : p)
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            return false;
    return true;
}

ParameterValues with(std::initializer_list<std::pair<Param, double>> changes)
{
    ParameterValues v = testParameters();
    for (const auto& [id, value] : changes)
        EXPECT_TRUE(v.set(id, value).empty()) << parameterInfo(id).key;
    return v;
}

} // namespace

TEST(Physics, SegmentsKeepTheirLengthUnderGravityAndStrongWind)
{
    auto sim
        = makeSimulation(with({ { Param::WindSpeed, 30.0 }, { Param::WindAzimuth, 0.0 }, { Param::Turbulence, 0.5 } }));
    run(*sim, 1000);
    EXPECT_LT(worstStretch(*sim), 0.01);
    EXPECT_EQ(sim->solver().strandsReset(), 0u);
}

TEST(Physics, NoParticleEndsDeeperThanOneMillimetreInsideTheHead)
{
    auto sim = makeSimulation(with({}));
    run(*sim, 300);
    // Judge against the mesh itself, not the baked field: nearest surface point and its normal.
    const MeshBvh bvh(defaultHead().mesh);
    std::vector<glm::vec3> p;
    sim->copySimulated(p);
    double deepest = 0.0;
    for (const glm::vec3& x : p) {
        const MeshBvh::ClosestPoint c = bvh.closestPoint(x);
        const glm::vec3 n = faceNormal(defaultHead().mesh, c.surface.triangle);
        if (glm::dot(x - c.point, n) < 0.0f)
            deepest = std::max(deepest, static_cast<double>(c.distance));
    }
    EXPECT_LT(deepest, 0.001);
}

TEST(Physics, StrongerGravityHangsTipsLowerAndMovesThemLess)
{
    // Under the same gusty wind, heavier hair hangs lower and sways less (Fig. 7 of the paper).
    double tipY[2], sway[2];
    const double gravities[2] = { 9.8, 17.8 };
    for (int i = 0; i < 2; ++i) {
        auto sim = makeSimulation(
            with({ { Param::Gravity, gravities[i] }, { Param::WindSpeed, 6.0 }, { Param::Turbulence, 1.0 } }));
        run(*sim, 240);
        double travelled = 0.0;
        glm::vec3 last = tipStats(*sim).meanTip;
        for (int k = 0; k < 120; ++k) {
            sim->step();
            const glm::vec3 now = tipStats(*sim).meanTip;
            travelled += glm::distance(now, last);
            last = now;
        }
        tipY[i] = last.y;
        sway[i] = travelled;
    }
    EXPECT_LT(tipY[1], tipY[0]);
    EXPECT_LT(sway[1], sway[0]);
}

TEST(Physics, NegativeGravityFloatsTipsAboveTheRoots)
{
    auto sim = makeSimulation(with({ { Param::Gravity, -2.8 }, { Param::Stiffness, 0.05 } }));
    run(*sim, 600);
    const TipStats s = tipStats(*sim);
    EXPECT_GT(s.meanTip.y, s.meanRoot.y + 0.05f);
}

TEST(Physics, WindMovesTipsItsWayFurtherWhenFaster)
{
    auto settle = [](double speed, double azimuth, double elevation) {
        auto sim = makeSimulation(with({ { Param::WindSpeed, speed }, { Param::WindAzimuth, azimuth },
            { Param::WindElevation, elevation }, { Param::Drag, 2.0 } }));
        run(*sim, 400);
        return tipStats(*sim).meanTip;
    };
    const glm::vec3 calm = settle(0.0, 0.0, 0.0);
    const glm::vec3 toRight = settle(8.0, 0.0, 0.0); // blows toward +X
    const glm::vec3 toRightFast = settle(16.0, 0.0, 0.0);
    const glm::vec3 toLeft = settle(8.0, 180.0, 0.0); // toward -X
    const glm::vec3 up = settle(8.0, 0.0, 90.0); // toward +Y
    EXPECT_GT(toRight.x, calm.x + 0.02f);
    EXPECT_GT(toRightFast.x, toRight.x + 0.01f);
    EXPECT_LT(toLeft.x, calm.x - 0.02f);
    EXPECT_GT(up.y, calm.y + 0.02f);
}

TEST(Physics, RootsStayOnTheScalp)
{
    auto sim = makeSimulation(with({ { Param::WindSpeed, 20.0 }, { Param::Turbulence, 1.0 } }));
    run(*sim, 200);
    std::vector<glm::vec3> p;
    sim->copySimulated(p);
    const Groom& g = sim->groom();
    const HairCurves keys = keyRestCurves(g);
    for (std::size_t w = 0; w < g.wispCount(); ++w) {
        const glm::vec3 root = p[keys.offsets[w]];
        EXPECT_LT(glm::distance(root, pointOn(defaultHead().mesh, g.roots[g.keyStrand[w]])), 1e-6f);
    }
}

TEST(Physics, RootsFollowTheHeadTransform)
{
    auto sim = makeSimulation(with({}));
    const glm::vec3 shift(0.05f, 0.02f, -0.01f);
    glm::mat4 m(1.0f);
    m[3] = glm::vec4(shift, 1.0f);
    sim->solver().setHeadTransform(m);
    run(*sim, 30);
    std::vector<glm::vec3> p;
    sim->copySimulated(p);
    const Groom& g = sim->groom();
    const HairCurves keys = keyRestCurves(g);
    for (std::size_t w = 0; w < g.wispCount(); ++w)
        EXPECT_LT(
            glm::distance(p[keys.offsets[w]], pointOn(defaultHead().mesh, g.roots[g.keyStrand[w]]) + shift), 1e-5f);
    EXPECT_LT(worstStretch(*sim), 0.01);
}

// The head turned a quarter turn about the vertical (gravity's axis, so the scene is only turned):
// the hair lands where the upright head's hair does, turned. The turned head's contact looks the
// field up in head space and turns its normals back into the world; a normal left in head space
// pushes hair lying on the head the wrong way.
TEST(Physics, ATurnedHeadGivesTheUprightHeadsHairTurned)
{
    const glm::mat4 quarterTurn(
        glm::vec4(0, 0, -1, 0), glm::vec4(0, 1, 0, 0), glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, 0, 1));
    auto upright = makeSimulation(with({}));
    auto turned = makeSimulation(with({}));
    turned->solver().setHeadTransform(quarterTurn);
    turned->resetToRest();
    run(*upright, 90);
    run(*turned, 90);
    std::vector<glm::vec3> a, b;
    upright->copySimulated(a);
    turned->copySimulated(b);
    ASSERT_EQ(a.size(), b.size());
    float worst = 0.0f;
    for (std::size_t k = 0; k < a.size(); ++k)
        worst = std::max(worst, glm::distance(glm::vec3(quarterTurn * glm::vec4(a[k], 1.0f)), b[k]));
    EXPECT_LT(worst, 1e-4f) << "metres";
}

TEST(Physics, SameResultWithOneAndTwoThreads)
{
    const ParameterValues v = with({ { Param::WindSpeed, 10.0 }, { Param::Turbulence, 1.0 } });
    auto one = makeSimulation(v, 1);
    auto two = makeSimulation(v, 2);
    ASSERT_EQ(one->solver().threadCount(), 1);
    ASSERT_EQ(two->solver().threadCount(), 2);
    run(*one, 200);
    run(*two, 200);
    std::vector<glm::vec3> a, b;
    one->copySimulated(a);
    two->copySimulated(b);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)));
}

TEST(Physics, HostileSettingsGiveNoNanAndLittleStretch)
{
    auto sim = makeSimulation(with({ { Param::TimeStep, 1.0 / 15.0 }, { Param::Gravity, 50.0 },
        { Param::WindSpeed, 50.0 }, { Param::Turbulence, 1.0 }, { Param::Substeps, 1 } }));
    run(*sim, 300);
    EXPECT_TRUE(allFinite(*sim));
    EXPECT_LT(worstStretch(*sim), 0.05);
}

TEST(Physics, ABrokenStrandIsResetAndDoesNotSpread)
{
    // Volume 0: strands that do not interact must not change by a bit (with volume on, the others
    // feel the broken strand leave the grid; VolumeTest checks that nothing goes non-finite).
    const ParameterValues v = with({ { Param::Volume, 0.0 } });
    auto broken = makeSimulation(v, 2);
    auto reference = makeSimulation(v, 2);
    run(*broken, 20);
    run(*reference, 20);
    broken->solver().moveParticle(3, 5, glm::vec3(NAN));
    broken->step();
    reference->step();
    EXPECT_EQ(broken->solver().strandsReset(), 1u);
    EXPECT_TRUE(allFinite(*broken));
    std::vector<glm::vec3> a, b;
    broken->copySimulated(a);
    reference->copySimulated(b);
    const HairCurves keys = keyRestCurves(broken->groom());
    for (std::size_t s = 0; s < keys.strandCount(); ++s) {
        const bool same
            = std::memcmp(a.data() + keys.offsets[s], b.data() + keys.offsets[s], keys.pointsIn(s) * sizeof(glm::vec3))
            == 0;
        if (s == 3) // back at its rest shape
            for (std::uint32_t j = keys.offsets[s]; j < keys.offsets[s + 1]; ++j)
                EXPECT_LT(glm::distance(a[j], keys.positions[j]), 1e-5f);
        else
            EXPECT_TRUE(same) << "strand " << s << " was disturbed by the broken one";
    }
}

TEST(Physics, ResetReturnsToRest)
{
    auto sim = makeSimulation(with({ { Param::WindSpeed, 10.0 } }));
    run(*sim, 50);
    sim->resetToRest();
    std::vector<glm::vec3> p;
    sim->copySimulated(p);
    const HairCurves keys = keyRestCurves(sim->groom());
    for (std::size_t i = 0; i < p.size(); ++i)
        EXPECT_LT(glm::distance(p[i], keys.positions[i]), 1e-5f);
}
