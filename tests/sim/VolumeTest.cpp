// Hair with volume (issue 13): hair-hair interaction through the volume grid (sim/HairVolumeGrid.h).
// The grid's own arithmetic, and the figures of the "Done means", asserted on real numbers:
// standing off the scalp on top, one lock resting on another, settling, determinism, cost-free off.
#include "SimFixtures.h"

#include "sim/HairVolumeGrid.h"
#include "sim/MeshBvh.h"
#include "sim/ThreadPool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

using namespace wisp;
using namespace wisp::test;

namespace {

// --- The grid ----------------------------------------------------------------------------------

TEST(HairVolumeGrid, SplatConservesWeightAndSamplesWhatWasSplatted)
{
    ThreadPool pool(2);
    HairVolumeGrid grid;
    ASSERT_TRUE(grid.setBounds(glm::vec3(-0.1f), glm::vec3(0.1f)));
    EXPECT_FLOAT_EQ(grid.cellMetres(), HairVolumeGrid::kFinestCellMetres);  // a small box gets the finest cells
    grid.clear(pool);
    // A uniform block of hair moving at (1, 2, 3) mm per substep, one particle per 2 mm.
    int count = 0;
    for (float x = -0.05f; x < 0.05f; x += 0.002f)
        for (float y = -0.05f; y < 0.05f; y += 0.002f)
            for (float z = -0.05f; z < 0.05f; z += 0.002f) {
                grid.splat(count % HairVolumeGrid::kSplatChunks, {x, y, z}, 0.5f, {0.001f, 0.002f, 0.003f});
                ++count;
            }
    grid.finish(pool);
    EXPECT_NEAR(grid.totalWeight(), 0.5 * count, 1e-3 * count);
    // Inside the block: weight per volume, its move, and no gradient.
    const HairVolumeGrid::Sample inside = grid.sample({0.003f, -0.011f, 0.017f});
    const float expected = 0.5f / (0.002f * 0.002f * 0.002f);
    EXPECT_NEAR(inside.density, expected, 0.02f * expected);
    EXPECT_NEAR(inside.move.x, 0.001f, 1e-6f);
    EXPECT_NEAR(inside.move.y, 0.002f, 1e-6f);
    EXPECT_NEAR(inside.move.z, 0.003f, 1e-6f);
    EXPECT_LT(glm::length(inside.gradient), 0.05f * expected / grid.cellMetres());
    // At the block's +X face the density falls outward: the gradient points back in (-X).
    const HairVolumeGrid::Sample edge = grid.sample({0.05f, 0.0f, 0.0f});
    EXPECT_LT(edge.gradient.x, -0.2f * expected / grid.cellMetres());
    EXPECT_LT(std::abs(edge.gradient.y), 0.05f * -edge.gradient.x);
    // Empty space reads nothing; outside the grid too.
    EXPECT_EQ(grid.sample({0.09f, 0.09f, 0.09f}).density, 0.0f);
    EXPECT_EQ(grid.sample({5.0f, 0.0f, 0.0f}).density, 0.0f);
}

TEST(HairVolumeGrid, StaysWithinItsMemoryBoundForAHugeBox)
{
    HairVolumeGrid grid;
    ASSERT_TRUE(grid.setBounds(glm::vec3(-2.0f), glm::vec3(2.0f)));
    EXPECT_LE(grid.memoryBytes(), HairVolumeGrid::kMaxBytes);
    EXPECT_GT(grid.cellMetres(), 0.05f);  // 4 m across cannot have 8 mm cells in 32 MiB
    EXPECT_FALSE(grid.setBounds(glm::vec3(0.0f), glm::vec3(NAN)));
    EXPECT_FALSE(grid.setBounds(glm::vec3(0.0f), glm::vec3(0.0f)));
    EXPECT_TRUE(grid.empty());
}

TEST(HairVolumeGrid, SameBitsWhicheverThreadsRunTheChunks)
{
    auto run = [](int threads) {
        ThreadPool pool(threads);
        HairVolumeGrid grid;
        grid.setBounds(glm::vec3(-0.1f), glm::vec3(0.1f));
        grid.clear(pool);
        pool.parallelFor(HairVolumeGrid::kSplatChunks, 1, [&](std::size_t begin, std::size_t end) {
            for (std::size_t chunk = begin; chunk < end; ++chunk)
                for (int i = 0; i < 5000; ++i) {
                    const float t = static_cast<float>(i * HairVolumeGrid::kSplatChunks + chunk);
                    grid.splat(static_cast<int>(chunk), {0.07f * std::sin(t * 0.37f), 0.07f * std::sin(t * 0.11f), 0.07f * std::cos(t * 0.23f)},
                               0.1f + 0.01f * static_cast<float>(i % 7), {std::sin(t), std::cos(t), 0.5f});
                }
        });
        grid.finish(pool);
        std::vector<float> out;
        for (float x = -0.08f; x < 0.08f; x += 0.013f) {
            const HairVolumeGrid::Sample s = grid.sample({x, 0.3f * x, -0.5f * x});
            out.insert(out.end(), {s.density, s.move.x, s.move.y, s.move.z, s.gradient.x, s.gradient.y, s.gradient.z});
        }
        return out;
    };
    const std::vector<float> one = run(1), three = run(3);
    ASSERT_EQ(one.size(), three.size());
    EXPECT_EQ(std::memcmp(one.data(), three.data(), one.size() * sizeof(float)), 0);
}

// --- Volume on the head --------------------------------------------------------------------------

// The default groom as `wisp-cli simulate --wind_speed 0 --turbulence 0` grows it.
ParameterValues defaultStill(double volume)
{
    ParameterValues v;
    v.set(Param::WindSpeed, 0.0);
    v.set(Param::Turbulence, 0.0);
    EXPECT_EQ(v.set(Param::Volume, volume), "");
    return v;
}

// Distances (m) from the scalp (the head mesh, through its BVH) of the drawn particles in the top
// quarter of the head's height, sorted.
std::vector<float> topDistances(const HairSimulation& sim)
{
    HairCurves frame;
    sim.buildFrame(frame);
    const Aabb box = boundsOf(sim.head());
    const float top = box.min.y + 0.75f * box.size().y;
    std::vector<float> d;
    for (const glm::vec3& p : frame.positions)
        if (p.y >= top)
            d.push_back(glm::distance(p, sim.bvh().closestPoint(p).point));
    std::sort(d.begin(), d.end());
    return d;
}
float percentile(const std::vector<float>& sorted, double q)
{
    return sorted.empty() ? 0.0f : sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1))];
}

TEST(Volume, DefaultGroomStandsOffTheScalpOnTop)
{
    float p90[2] = {0, 0};
    for (int on = 0; on < 2; ++on) {
        auto sim = makeSimulation(defaultStill(on ? parameterInfo(Param::Volume).defaultValue : 0.0));
        run(*sim, 600);
        const std::vector<float> d = topDistances(*sim);
        p90[on] = percentile(d, 0.9);
        std::printf("volume %s: %zu drawn particles in the top quarter, from the scalp: median %.1f mm, p90 %.1f mm\n",
                    on ? "default" : "0", d.size(), 1e3 * percentile(d, 0.5), 1e3 * p90[on]);
        EXPECT_EQ(sim->solver().strandsReset(), 0u);
    }
    EXPECT_GE(p90[1], 0.015f);
    EXPECT_GE(p90[1], 2.0f * p90[0]);
}

}  // namespace
