// The memory floor's sweep (FloorSweep.h) does the work it claims, so `wisp-cli bench`'s floor
// row times a real hair step: strands hang at their length from fixed roots, a push swings and
// dies out, and the result is the same on 1 and 2 threads and on every SIMD target.
#include "sim/solver/FloorSweep.h"
#include "sim/util/SimdTarget.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>
#include <vector>

using namespace wisp;

TEST(FloorSweep, RoundsUpToWholeStrandsOfTheGivenLength)
{
    const FloorSweep floor(1000, 15, 1);
    EXPECT_EQ(floor.strandCount(), 67u); // 1000 / 15 rounded up
    EXPECT_EQ(floor.particleCount(), 1005u);
    EXPECT_NEAR(floor.segmentMetres(), 0.3f / 14.0f, 1e-7f);
    EXPECT_EQ(floor.bytesPerStep(), 5u * 15u * 6u * 16u * sizeof(float) * 2u); // 5 blocks of 16 strands
    EXPECT_EQ(FloorSweep(1, 1, 1).pointsPerStrand(), 2u);
}

TEST(FloorSweep, StrandsHangAtTheirLengthFromFixedRoots)
{
    FloorSweep floor(1000, 15, 2);
    for (int i = 0; i < 60; ++i)
        floor.step();
    for (std::size_t s = 0; s < floor.strandCount(); ++s) {
        EXPECT_FLOAT_EQ(floor.x(s, 0), 0.01f * static_cast<float>(s)) << "strand " << s << "'s root moved";
        EXPECT_FLOAT_EQ(floor.y(s, 0), 0.0f);
        EXPECT_NEAR(floor.y(s, 14), -0.3f, 1e-4f) << "strand " << s;
    }
}

TEST(FloorSweep, APushSwingsEveryParticleAndKeepsEverySegmentsLength)
{
    FloorSweep floor(32 * 15, 15, 2);
    floor.displace(0.05f, 0.02f);
    double moved = 0.0;
    float worstStretch = 0.0f;
    for (int i = 0; i < 30; ++i) {
        const float before = floor.x(3, 14);
        floor.step();
        moved += std::abs(floor.x(3, 14) - before);
        for (std::uint32_t j = 1; j < 15; ++j) {
            const float dx = floor.x(3, j) - floor.x(3, j - 1), dy = floor.y(3, j) - floor.y(3, j - 1),
                        dz = floor.z(3, j) - floor.z(3, j - 1);
            worstStretch = std::max(
                worstStretch, std::abs(std::sqrt(dx * dx + dy * dy + dz * dz) / floor.segmentMetres() - 1.0f));
        }
    }
    EXPECT_GT(moved, 0.01) << "the pushed tip did not swing";
    EXPECT_LT(worstStretch, 1e-4f);
}

TEST(FloorSweep, OneAndTwoThreadsGiveTheSameBits)
{
    FloorSweep one(5000, 15, 1), two(5000, 15, 2);
    one.displace(0.03f, -0.01f);
    two.displace(0.03f, -0.01f);
    for (int i = 0; i < 20; ++i) {
        one.step();
        two.step();
    }
    for (std::size_t s = 0; s < one.strandCount(); ++s)
        for (std::uint32_t j = 0; j < 15; ++j) {
            ASSERT_EQ(one.x(s, j), two.x(s, j));
            ASSERT_EQ(one.y(s, j), two.y(s, j));
            ASSERT_EQ(one.z(s, j), two.z(s, j));
        }
}

// The floor runs on the solver's SIMD target, a register's width of lanes at a time: every target
// this CPU runs sweeps the same lanes to the same bits (exact square roots and divisions, as the
// solver's, SolverLanes-inl.h), so no target's floor skips or repeats a slice of a block.
TEST(FloorSweep, EveryTargetGivesTheSameBits)
{
    auto sweep = [] {
        FloorSweep floor(16 * 15 * 3 + 7, 15, 2); // three blocks and a padded fourth
        floor.displace(0.03f, -0.02f);
        for (int i = 0; i < 30; ++i)
            floor.step();
        std::vector<float> bits;
        for (std::size_t s = 0; s < floor.strandCount(); ++s)
            for (std::uint32_t j = 0; j < floor.pointsPerStrand(); ++j)
                bits.insert(bits.end(), { floor.x(s, j), floor.y(s, j), floor.z(s, j) });
        return bits;
    };
    const std::vector<std::string> targets = availableSimdTargets();
    ASSERT_FALSE(targets.empty());
    const std::vector<float> best = sweep();
    for (const std::string& t : targets) {
        struct Forced { // the best target back whatever fails below
            ~Forced() { forceSimdTarget(""); }
        } forced;
        ASSERT_EQ(forceSimdTarget(t), "");
        const std::vector<float> here = sweep();
        ASSERT_EQ(here.size(), best.size());
        std::size_t differing = 0;
        for (std::size_t i = 0; i < best.size(); ++i)
            differing += here[i] != best[i] ? 1 : 0;
        EXPECT_EQ(differing, 0u) << t;
    }
    // And the sweep moved them (a sweep that skipped a slice would leave its lanes where they hung).
    const FloorSweep still(16 * 15 * 3 + 7, 15, 1);
    std::size_t moved = 0;
    for (std::size_t s = 0; s < still.strandCount(); ++s)
        moved += std::abs(best[3 * (s * 15 + 14)] - still.x(s, 14)) > 1e-3f ? 1 : 0;
    EXPECT_EQ(moved, still.strandCount());
}

// The bench times the floor between a solver's steps on the solver's own pool: the sweep on a pool
// it is given runs on that pool's threads and gives the same bits as on a pool of its own.
TEST(FloorSweep, OnASharedPoolItRunsOnThatPoolAndGivesTheSameBits)
{
    ThreadPool shared(3);
    FloorSweep own(5000, 15, 1), onShared(5000, 15, shared);
    EXPECT_EQ(onShared.threadCount(), shared.threadCount());
    own.displace(0.02f, 0.01f);
    onShared.displace(0.02f, 0.01f);
    std::atomic<int> otherLoops{ 0 };
    for (int i = 0; i < 20; ++i) {
        own.step();
        onShared.step();
        // The pool is still the caller's to use between the sweep's steps.
        shared.parallelFor(8, 1, [&](std::size_t, std::size_t) { otherLoops.fetch_add(1); });
    }
    EXPECT_EQ(otherLoops.load(), 160);
    for (std::size_t s = 0; s < own.strandCount(); ++s)
        for (std::uint32_t j = 0; j < 15; ++j) {
            ASSERT_EQ(own.x(s, j), onShared.x(s, j));
            ASSERT_EQ(own.y(s, j), onShared.y(s, j));
            ASSERT_EQ(own.z(s, j), onShared.z(s, j));
        }
}
