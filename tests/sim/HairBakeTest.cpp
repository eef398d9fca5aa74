// Baking a frame range: every frame kept, the head's pose with it, bounded memory, cancel, and
// the same frames whether a range is baked whole or in parts.
#include "SimFixtures.h"

#include "sim/motion/HairBake.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace wisp;
using namespace wisp::test;

namespace {

HeadMotion shake()
{
    HeadMotion m;
    m.setProcedural(motionPreset(MotionKind::Shake));
    return m;
}

BakeOptions quick(int first, int last)
{
    BakeOptions o;
    o.range = { first, last, 24.0 };
    o.drapeFirst = false; // the drape has its own tests; these measure the bake
    return o;
}

} // namespace

TEST(HairBake, StepsDivideEachFrame)
{
    int n = 0;
    EXPECT_DOUBLE_EQ(bakeStepSeconds(24.0, 1.0 / 60.0, &n), 1.0 / 72.0);
    EXPECT_EQ(n, 3);
    EXPECT_DOUBLE_EQ(bakeStepSeconds(60.0, 1.0f / 60.0f, &n), 1.0 / 60.0);
    EXPECT_EQ(n, 1);
    EXPECT_DOUBLE_EQ(bakeStepSeconds(30.0, 1.0 / 60.0, &n), 1.0 / 60.0);
    EXPECT_EQ(n, 2);
}

TEST(HairBake, KeepsEveryFrameWithTheHeadAndTheTipsMove)
{
    auto sim = makeSimulation(testParameters());
    const glm::vec3 pivot = pivotOf(defaultHead().mesh);
    int progressCalls = 0, lastDone = 0;
    BakeOptions o = quick(1, 12);
    o.progress = [&](int done, int total) {
        ++progressCalls;
        lastDone = done;
        EXPECT_EQ(total, 12);
    };
    const BakeResult r = bakeMotion(*sim, shake(), pivot, o);
    ASSERT_EQ(r.error, "");
    ASSERT_TRUE(r.cache.complete());
    EXPECT_EQ(progressCalls, 12);
    EXPECT_EQ(lastDone, 12);
    EXPECT_EQ(r.stepsRun, 11u * 3u);
    EXPECT_EQ(r.cache.pointCount(), sim->groom().rest.pointCount());
    EXPECT_EQ(r.cache.memoryBytes(), 12 * r.cache.bytesPerFrame());
    const HairCurves& rest = sim->groom().rest;
    double tipTravel = 0.0;
    for (int f = 1; f <= 12; ++f) {
        const BakedFrame* frame = r.cache.find(f);
        ASSERT_NE(frame, nullptr);
        EXPECT_EQ(frame->frame, f);
        ASSERT_EQ(frame->positions.size(), rest.pointCount());
        // The roots sit on the head where its transform put it.
        for (std::size_t s = 0; s < rest.strandCount(); s += 7) {
            const glm::vec3 root(frame->headToWorld * glm::vec4(rest.positions[rest.offsets[s]], 1.0f));
            ASSERT_LT(glm::distance(frame->positions[rest.offsets[s]], root), 1e-4f)
                << "frame " << f << " strand " << s;
        }
        if (f > 1) {
            const BakedFrame& before = *r.cache.find(f - 1);
            for (std::size_t s = 0; s < rest.strandCount(); ++s)
                tipTravel += glm::distance(
                    frame->positions[rest.offsets[s + 1] - 1], before.positions[rest.offsets[s + 1] - 1]);
        }
    }
    // The head shakes 30 degrees: the tips travel centimetres per frame on average.
    EXPECT_GT(tipTravel / (11.0 * static_cast<double>(rest.strandCount())), 0.002);
    EXPECT_EQ(r.cache.find(13), nullptr);
    EXPECT_EQ(r.cache.curvesAt(5).positions, r.cache.find(5)->positions);
    // The simulation's own time step is back.
    EXPECT_FLOAT_EQ(sim->solver().settings().timeStepSeconds, testParameters().getFloat(Param::TimeStep));
}

TEST(HairBake, APartOfTheRangeGivesTheSameFramesAsTheWhole)
{
    const glm::vec3 pivot = pivotOf(defaultHead().mesh);
    auto a = makeSimulation(testParameters(), 1);
    auto b = makeSimulation(testParameters(), 2);
    const BakeResult whole = bakeMotion(*a, shake(), pivot, quick(1, 10));
    const BakeResult part = bakeMotion(*b, shake(), pivot, quick(7, 10));
    ASSERT_EQ(whole.error, "");
    ASSERT_EQ(part.error, "");
    ASSERT_EQ(part.cache.frames.size(), 4u);
    for (int f = 7; f <= 10; ++f) {
        const auto& x = whole.cache.find(f)->positions;
        const auto& y = part.cache.find(f)->positions;
        ASSERT_EQ(x.size(), y.size());
        EXPECT_EQ(0, std::memcmp(x.data(), y.data(), x.size() * sizeof(glm::vec3))) << "frame " << f;
    }
}

TEST(HairBake, RefusesABakeOverTheMemoryBoundBeforeSimulating)
{
    auto sim = makeSimulation(testParameters());
    BakeOptions o = quick(1, 100);
    o.memoryBoundBytes = 50 * bytesPerBakedFrame(sim->groom().rest.pointCount(), sim->groom().strandCount());
    const BakeResult r = bakeMotion(*sim, shake(), glm::vec3(0.0f), o);
    EXPECT_NE(
        r.error.find("a bake of 100 frames of " + std::to_string(sim->groom().rest.pointCount()) + " points needs"),
        std::string::npos)
        << r.error;
    EXPECT_NE(r.error.find("more than the bake's memory bound"), std::string::npos);
    EXPECT_EQ(r.stepsRun, 0u);
    EXPECT_TRUE(r.cache.frames.empty());
    // Streamed (not kept), the same range needs no bound.
    o.keepFrames = false;
    o.range = { 1, 3, 24.0 };
    int streamed = 0;
    o.onFrame = [&](const BakedFrame& f, const BakeCache& layout) {
        EXPECT_EQ(f.positions.size(), layout.pointCount());
        ++streamed;
        return std::string();
    };
    const BakeResult s = bakeMotion(*sim, shake(), glm::vec3(0.0f), o);
    EXPECT_EQ(s.error, "");
    EXPECT_EQ(streamed, 3);
    EXPECT_TRUE(s.cache.frames.empty());
}

TEST(HairBake, CancelStopsBetweenSteps)
{
    auto sim = makeSimulation(testParameters());
    BakeOptions o = quick(1, 48);
    int asked = 0;
    o.cancelled = [&] { return ++asked > 10; };
    const BakeResult r = bakeMotion(*sim, shake(), glm::vec3(0.0f), o);
    EXPECT_TRUE(r.cancelled);
    // Asked once after the drape, then before each step: 9 steps ran.
    EXPECT_EQ(r.stepsRun, 9u);
    EXPECT_EQ(r.cache.frames.size(), 4u); // frame 1, then 3 steps a frame
    EXPECT_FALSE(r.cache.complete());
}

TEST(HairBake, RefusesBadRangesAndMotions)
{
    auto sim = makeSimulation(testParameters());
    BakeOptions o = quick(5, 2);
    EXPECT_EQ(bakeMotion(*sim, shake(), glm::vec3(0.0f), o).error, "frames 5:2: the last frame comes before the first");
    o.range = { 0, 2, 24.0 };
    EXPECT_EQ(bakeMotion(*sim, shake(), glm::vec3(0.0f), o).error, "frames 0:2: frames start at 1 (frame 1 is 0 s)");
    o.range = { 1, 2, 0.0 };
    EXPECT_EQ(bakeMotion(*sim, shake(), glm::vec3(0.0f), o).error, "fps 0 is outside 1..1000");
    o.range = { 1, 2, 24.0 };
    HeadMotion bad;
    bad.setProcedural({ MotionKind::Nod, -1.0, 1.0, 0.0 });
    EXPECT_EQ(
        bakeMotion(*sim, bad, glm::vec3(0.0f), o).error, "head motion: motion: amplitude -1 is outside 0..90 degrees");
}

// Issue 17: a cached frame is drawn as the live one was, so it keeps the hair's wetness (wet hair
// is darker and clumped); a dry bake keeps none.
TEST(HairBake, KeepsEachFramesWetnessAsItDries)
{
    ParameterValues v = testParameters();
    v.set(Param::DryingTime, 1.0); // half-life, s: visibly drier within half a second
    auto sim = makeSimulation(v);
    ASSERT_EQ(sim->applyForces(v), "");
    const BakeResult dry = bakeMotion(*sim, shake(), glm::vec3(0.0f), quick(1, 3));
    ASSERT_EQ(dry.error, "");
    for (const BakedFrame& f : dry.cache.frames)
        EXPECT_TRUE(f.wetness.empty()) << "frame " << f.frame;

    std::vector<std::uint64_t> keys;
    for (std::uint32_t strand : sim->groom().keyStrand)
        keys.push_back(sim->groom().strandIdentity(strand));
    sim->wet(keys, 1.0f);
    const BakeResult wet = bakeMotion(*sim, shake(), glm::vec3(0.0f), quick(1, 12));
    ASSERT_EQ(wet.error, "");
    ASSERT_TRUE(wet.cache.complete());
    const std::size_t strands = wet.cache.strandCount();
    ASSERT_EQ(strands, sim->groom().strandCount());
    const BakedFrame& first = wet.cache.frames.front();
    const BakedFrame& last = wet.cache.frames.back();
    ASSERT_EQ(first.wetness.size(), strands);
    ASSERT_EQ(last.wetness.size(), strands);
    EXPECT_GT(first.wetness[0], 0.9f);
    // 11 frames at 24 fps is 0.458 s: a 1 s half-life leaves 2^-0.458 = 0.73 of it.
    EXPECT_NEAR(last.wetness[0], first.wetness[0] * std::exp2(-11.0 / 24.0), 0.03);
    std::vector<float> now;
    sim->strandWetness(now);
    EXPECT_EQ(now, last.wetness) << "the simulation's state is the last frame's";
    EXPECT_EQ(wet.cache.bytesPerFrame(), sizeof(BakedFrame) + 12 * wet.cache.pointCount() + 4 * strands);
}
