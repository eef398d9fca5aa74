// The optional global shape (Solver.cpp, pullTowardGlobalShape; the global_shape parameter): a pull
// toward the groomed rest pose as the head carries it, full at the root and fading along the
// strand (Han & Harada 2012, as AMD TressFX). Off (0) by default.
#include "SimFixtures.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>

using namespace wisp;
using namespace wisp::test;

namespace {

ParameterValues windy(double globalShape)
{
    ParameterValues v = testParameters();
    EXPECT_EQ(v.set(Param::WindSpeed, 10.0), "");
    EXPECT_EQ(v.set(Param::WindAzimuth, 0.0), ""); // toward +x, across the hair
    EXPECT_EQ(v.set(Param::GlobalShape, globalShape), "");
    return v;
}

// Mean distance from the rest pose (head at identity) of particle `share` of the way along each
// simulated strand (1: the tips).
double meanDistanceFromRest(const HairSimulation& sim, double share)
{
    std::vector<glm::vec3> p;
    sim.copySimulated(p);
    const HairCurves rest = keyRestCurves(sim.groom());
    double sum = 0.0;
    for (std::size_t i = 0; i < rest.strandCount(); ++i) {
        const std::size_t j = static_cast<std::size_t>(share * static_cast<double>(rest.pointsIn(i) - 1) + 0.5);
        sum += glm::distance(p[rest.offsets[i] + j], rest.positions[rest.offsets[i] + j]);
    }
    return sum / static_cast<double>(rest.strandCount());
}

} // namespace

TEST(GlobalShape, IsOffByDefaultAndInTheRegistry)
{
    const ParameterInfo* info = findParameter("global_shape");
    ASSERT_NE(info, nullptr);
    EXPECT_EQ(info->defaultValue, 0.0);
    EXPECT_EQ(info->minimum, 0.0);
    EXPECT_EQ(info->maximum, 1.0);
    EXPECT_EQ(solverSettingsFrom(ParameterValues{}).globalShape, 0.0f);
    EXPECT_EQ(solverSettingsFrom(windy(0.7)).globalShape, 0.7f);
    EXPECT_NE(checkParameterValue(Param::GlobalShape, 1.5), "");
}

TEST(GlobalShape, HoldsTheGroomAgainstWindAndHoldsTheRootsMoreThanTheTips)
{
    auto free = makeSimulation(windy(0.0), 1);
    auto held = makeSimulation(windy(1.0), 1);
    run(*free, 180); // 3 s of 10 m/s wind
    run(*held, 180);
    const double freeTips = meanDistanceFromRest(*free, 1.0), heldTips = meanDistanceFromRest(*held, 1.0);
    const double heldNearRoot = meanDistanceFromRest(*held, 0.2), freeNearRoot = meanDistanceFromRest(*free, 0.2);
    std::printf("[ figures  ] 10 m/s wind, 3 s: tips %.1f mm from rest with global shape 0, %.1f mm with 1; "
                "a fifth along the strand %.1f and %.1f mm\n",
        freeTips * 1e3, heldTips * 1e3, freeNearRoot * 1e3, heldNearRoot * 1e3);
    EXPECT_GT(freeTips, 0.05) << "the wind hardly moved the free hair: the test proves nothing";
    EXPECT_LT(heldTips, 0.6 * freeTips) << "the global shape did not hold the tips";
    EXPECT_LT(heldNearRoot, 0.25 * heldTips) << "the pull does not fade along the strand";
    EXPECT_LT(heldNearRoot, 0.5 * freeNearRoot);
}

TEST(GlobalShape, FollowsTheHeadWhenItTurns)
{
    // The target is the rest pose as the head carries it: turned 90 degrees, held hair turns along.
    ParameterValues v = testParameters();
    ASSERT_EQ(v.set(Param::GlobalShape, 1.0), "");
    auto held = makeSimulation(v, 1);
    const glm::mat4 turned = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0));
    held->solver().setHeadTransform(turned);
    run(*held, 120);
    std::vector<glm::vec3> p;
    held->copySimulated(p);
    const HairCurves rest = keyRestCurves(held->groom());
    double sum = 0.0;
    for (std::size_t i = 0; i < rest.strandCount(); ++i) {
        const std::size_t j = rest.offsets[i] + 2; // near the root: held hardest
        sum += glm::distance(p[j], glm::vec3(turned * glm::vec4(rest.positions[j], 1.0f)));
    }
    EXPECT_LT(sum / static_cast<double>(rest.strandCount()), 0.003) << "the held pose did not turn with the head";
}

TEST(GlobalShape, GivesTheSameBitsOnOneThreadAndOnFour)
{
    auto one = makeSimulation(windy(1.0), 1);
    auto four = makeSimulation(windy(1.0), 4);
    run(*one, 60);
    run(*four, 60);
    std::vector<glm::vec3> a, b;
    one->copySimulated(a);
    four->copySimulated(b);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_TRUE(a == b) << "threads changed the result";
}

TEST(GlobalShape, HairStillSettlesWithItOn)
{
    // As SettlingTest's bar: after 10 s without wind, fewer than 1 % of tips still move 1 mm a step.
    for (const int substeps : { 1, 4 }) {
        ParameterValues v = testParameters();
        ASSERT_EQ(v.set(Param::GlobalShape, 1.0), "");
        ASSERT_EQ(v.set(Param::Substeps, substeps), "");
        auto sim = makeSimulation(v, 1);
        run(*sim, 600);
        std::vector<glm::vec3> before, after;
        sim->copySimulated(before);
        sim->step();
        sim->copySimulated(after);
        const HairCurves rest = keyRestCurves(sim->groom());
        std::size_t moving = 0;
        for (std::size_t i = 0; i < rest.strandCount(); ++i) {
            const std::size_t tip = rest.offsets[i + 1] - 1;
            moving += glm::distance(before[tip], after[tip]) > 1e-3f ? 1 : 0;
        }
        EXPECT_LT(static_cast<double>(moving), 0.01 * static_cast<double>(rest.strandCount()))
            << substeps << " substeps";
    }
}
