// Hair with volume (issue 13): hair-hair interaction through the volume grid (sim/solver/HairVolumeGrid.h).
// The grid's own arithmetic, and the figures of the "Done means", asserted on real numbers:
// standing off the scalp on top, one lock resting on another, settling, determinism, cost-free off.
#include "SimFixtures.h"

#include "sim/geometry/MeshBvh.h"
#include "sim/solver/HairVolumeGrid.h"
#include "sim/util/SimdTarget.h"
#include "sim/util/ThreadPool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace wisp;
using namespace wisp::test;

namespace {

// The volume that gives natural hair (README, "Hair volume"), the registry's default.
constexpr double kNaturalVolume = 0.5;

// --- The grid ----------------------------------------------------------------------------------

TEST(HairVolumeGrid, SplatConservesWeightAndSamplesWhatWasSplatted)
{
    ThreadPool pool(2);
    HairVolumeGrid grid;
    ASSERT_TRUE(grid.setBounds(glm::vec3(-0.1f), glm::vec3(0.1f)));
    EXPECT_FLOAT_EQ(grid.cellMetres(), HairVolumeGrid::kFinestCellMetres); // a small box gets the finest cells
    grid.setWeightBound(0.5 * 51 * 51 * 51);
    // A uniform block of hair moving at (1, 2, 3) mm per substep, one particle per 2 mm.
    int count = 0;
    for (float x = -0.05f; x < 0.05f; x += 0.002f)
        for (float y = -0.05f; y < 0.05f; y += 0.002f)
            for (float z = -0.05f; z < 0.05f; z += 0.002f) {
                grid.splat(0, { x, y, z }, 0.5f, { 0.001f, 0.002f, 0.003f });
                ++count;
            }
    grid.finish(&pool);
    EXPECT_NEAR(grid.totalWeight(), 0.5 * count, 1e-3 * count);
    // Inside the block: weight per volume, its move, and no gradient.
    const HairVolumeGrid::Sample inside = grid.sample({ 0.003f, -0.011f, 0.017f });
    const float expected = 0.5f / (0.002f * 0.002f * 0.002f);
    EXPECT_NEAR(inside.density, expected, 0.02f * expected);
    EXPECT_NEAR(inside.move.x, 0.001f, 1e-6f);
    EXPECT_NEAR(inside.move.y, 0.002f, 1e-6f);
    EXPECT_NEAR(inside.move.z, 0.003f, 1e-6f);
    EXPECT_LT(glm::length(inside.gradient), 0.05f * expected / grid.cellMetres());
    // At the block's +X face the density falls outward: the gradient points back in (-X).
    const HairVolumeGrid::Sample edge = grid.sample({ 0.05f, 0.0f, 0.0f });
    EXPECT_LT(edge.gradient.x, -0.2f * expected / grid.cellMetres());
    EXPECT_LT(std::abs(edge.gradient.y), 0.05f * -edge.gradient.x);
    // Empty space reads nothing; outside the grid too.
    EXPECT_EQ(grid.sample({ 0.09f, 0.09f, 0.09f }).density, 0.0f);
    EXPECT_EQ(grid.sample({ 5.0f, 0.0f, 0.0f }).density, 0.0f);
}

// A dense groom's kernel: each particle splats into its nearest node, and the sums are smoothed by
// [1 2 1]/4 along each axis: a particle's weight at its node (1/8 of it), the six beside (1/16), the
// twelve across an edge (1/32) and the eight across a corner (1/64); nothing two nodes away.
TEST(HairVolumeGrid, NearestSmoothedSpreadsAParticleOverItsNeighboursAndConservesWeight)
{
    ThreadPool pool(2);
    HairVolumeGrid grid;
    ASSERT_TRUE(grid.setBounds(
        glm::vec3(-0.1f), glm::vec3(0.1f), 1, HairVolumeGrid::kMaxNodes, HairVolumeGrid::Kernel::NearestSmoothed));
    EXPECT_EQ(grid.kernel(), HairVolumeGrid::Kernel::NearestSmoothed);
    grid.setWeightBound(10.0);
    const float h = grid.cellMetres();
    const glm::vec3 node = grid.origin() + h * glm::vec3(grid.dims() / 2);
    // 0.4 of a cell off the node each way: still its nearest.
    grid.splat(0, node + 0.4f * h * glm::vec3(1.0f, -1.0f, 1.0f), 2.0f, { 0.001f, 0.0f, -0.002f });
    // And one at the grid's corner node: its shares beyond the faces stay in the grid.
    grid.splat(0, grid.origin() + glm::vec3(0.1f * h), 1.0f, glm::vec3(0.0f));
    grid.finish(&pool);
    EXPECT_NEAR(grid.totalWeight(), 3.0, 1e-5);
    const float perVolume = 1.0f / (h * h * h);
    EXPECT_NEAR(grid.sample(node).density, 2.0f / 8.0f * perVolume, 1e-3f * perVolume);
    EXPECT_NEAR(grid.sample(node + glm::vec3(h, 0.0f, 0.0f)).density, 2.0f / 16.0f * perVolume, 1e-3f * perVolume);
    EXPECT_NEAR(grid.sample(node + glm::vec3(0.0f, -h, h)).density, 2.0f / 32.0f * perVolume, 1e-3f * perVolume);
    EXPECT_NEAR(grid.sample(node + glm::vec3(-h, h, h)).density, 2.0f / 64.0f * perVolume, 1e-3f * perVolume);
    EXPECT_EQ(grid.sample(node + glm::vec3(2.0f * h, 0.0f, 0.0f)).density, 0.0f);
    // Read at the nearest node: 0.3 of a cell off reads the node itself, its mean move too.
    const HairVolumeGrid::Sample near = grid.sample(node + glm::vec3(0.3f * h, -0.3f * h, 0.0f));
    EXPECT_EQ(near.density, grid.sample(node).density);
    EXPECT_NEAR(near.move.x, 0.001f, 1e-6f);
    EXPECT_NEAR(near.move.z, -0.002f, 1e-6f);
    // The gradient (central differences of the smoothed density) points back to the particle.
    EXPECT_LT(grid.sample(node + glm::vec3(h, 0.0f, 0.0f)).gradient.x, 0.0f);
    EXPECT_GT(grid.sample(node - glm::vec3(0.0f, 0.0f, h)).gradient.z, 0.0f);
    // The next pass without the particle leaves nothing behind (its bricks and those beside go empty).
    grid.finish(&pool);
    EXPECT_EQ(grid.totalWeight(), 0.0);
    EXPECT_EQ(grid.sample(node + glm::vec3(h, 0.0f, 0.0f)).density, 0.0f);
}

TEST(HairVolumeGrid, StaysWithinItsMemoryBoundForAHugeBox)
{
    HairVolumeGrid grid;
    ASSERT_TRUE(grid.setBounds(glm::vec3(-2.0f), glm::vec3(2.0f)));
    EXPECT_LE(grid.memoryBytes(), HairVolumeGrid::kMaxBytes);
    EXPECT_GT(grid.cellMetres(), 0.05f); // 4 m across cannot have 8 mm cells in 32 MiB
    ASSERT_TRUE(grid.setBounds(glm::vec3(-2.0f), glm::vec3(2.0f), HairVolumeGrid::kMaxSlots, HairVolumeGrid::kMaxNodes,
        HairVolumeGrid::Kernel::NearestSmoothed));
    EXPECT_LE(grid.memoryBytes(), HairVolumeGrid::kMaxBytes);
    EXPECT_FALSE(grid.setBounds(glm::vec3(0.0f), glm::vec3(NAN)));
    EXPECT_FALSE(grid.setBounds(glm::vec3(0.0f), glm::vec3(0.0f)));
    EXPECT_TRUE(grid.empty());
}

// Each thread splats into a slot of its own in fixed point: the same bits whichever thread splats
// which particle, in whatever order (the pool hands out ranges as threads come free).
TEST(HairVolumeGrid, SameBitsWhicheverThreadsSplatWhichParticles)
{
    for (const HairVolumeGrid::Kernel kernel :
        { HairVolumeGrid::Kernel::Trilinear, HairVolumeGrid::Kernel::NearestSmoothed }) {
        auto run = [kernel](int threads) {
            ThreadPool pool(threads);
            HairVolumeGrid grid;
            grid.setBounds(glm::vec3(-0.1f), glm::vec3(0.1f), threads, HairVolumeGrid::kMaxNodes, kernel);
            EXPECT_EQ(grid.slots(), threads);
            grid.setWeightBound(0.2 * 40'000);
            pool.parallelFor(40'000, 7, [&](std::size_t begin, std::size_t end) {
                const int slot = grid.claimSlot();
                for (std::size_t i = begin; i < end; ++i) {
                    const float t = static_cast<float>(i);
                    grid.splat(slot,
                        { 0.07f * std::sin(t * 0.37f), 0.07f * std::sin(t * 0.11f), 0.07f * std::cos(t * 0.23f) },
                        0.1f + 0.01f * static_cast<float>(i % 7), { 0.01f * std::sin(t), 0.01f * std::cos(t), 0.005f });
                }
                grid.releaseSlot(slot);
            });
            grid.finish(&pool);
            std::vector<float> out;
            for (float x = -0.08f; x < 0.08f; x += 0.013f) {
                const HairVolumeGrid::Sample s = grid.sample({ x, 0.3f * x, -0.5f * x });
                out.insert(
                    out.end(), { s.density, s.move.x, s.move.y, s.move.z, s.gradient.x, s.gradient.y, s.gradient.z });
            }
            return out;
        };
        const std::vector<float> one = run(1), three = run(3);
        ASSERT_EQ(one.size(), three.size());
        EXPECT_EQ(std::memcmp(one.data(), three.data(), one.size() * sizeof(float)), 0);
        EXPECT_GT(*std::max_element(one.begin(), one.end()), 1000.0f); // it read real hair
    }
}

// The splats' fixed point on every SIMD target (the float-to-64-bit conversion is one instruction
// on AVX-512, the float's fields shifted on AVX2, lane by lane on SSE4): rows of sixteen, some lanes
// sharing a cell, with weights from one that fills the fixed point's range (its values near 2^60)
// to ones a few units wide, and moves of both signs up to the clamp. Every target reads back the
// same bits, and the weight splatted is the weight read back.
TEST(HairVolumeGrid, EveryTargetSplatsTheSameFixedPointFromAFewUnitsToTheTopOfItsRange)
{
    for (const HairVolumeGrid::Kernel kernel :
        { HairVolumeGrid::Kernel::Trilinear, HairVolumeGrid::Kernel::NearestSmoothed }) {
        double splatted = 0.0;
        auto run = [&](const std::string& target) {
            EXPECT_EQ(forceSimdTarget(target), "");
            HairVolumeGrid grid;
            grid.setBounds(glm::vec3(-0.1f), glm::vec3(0.1f), 1, HairVolumeGrid::kMaxNodes, kernel);
            grid.setWeightBound(1.0); // units of 2^-60
            alignas(64) float x[16], y[16], z[16], w[16], mx[16], my[16], mz[16];
            splatted = 0.0;
            for (int row = 0; row < 8; ++row) {
                for (int l = 0; l < 16; ++l) {
                    const float t = static_cast<float>(row * 16 + l);
                    x[l] = 0.002f * static_cast<float>(l / 3) - 0.01f; // three lanes a cell, or two
                    y[l] = 0.05f * std::sin(t * 0.37f);
                    z[l] = 0.05f * std::cos(t * 0.23f);
                    // One heavy particle a row, the rest from 1e-3 down to 3e-18 (a few units).
                    w[l] = l == 5 ? 0.1f : 1e-3f * std::pow(1e-1f, static_cast<float>(l % 16));
                    mx[l] = 0.7f * std::sin(t); // beyond the clamp (0.5 m) now and then
                    my[l] = -0.3f * std::cos(t * 1.3f);
                    mz[l] = l % 2 ? -1e-6f : 0.49f;
                    splatted += static_cast<double>(w[l]);
                }
                grid.splatRow(0, x, y, z, w, mx, my, mz);
            }
            grid.finish(nullptr);
            EXPECT_NEAR(grid.totalWeight(), splatted, 1e-6 * splatted) << target;
            std::vector<float> out;
            for (float px = -0.02f; px < 0.01f; px += 0.0013f)
                for (float py = -0.05f; py < 0.05f; py += 0.007f) {
                    const HairVolumeGrid::Sample s = grid.sample({ px, py, 0.6f * py });
                    out.insert(out.end(), { s.density, s.hair, s.move.x, s.move.y, s.move.z, s.gradient.x });
                }
            return out;
        };
        const std::vector<std::string> targets = availableSimdTargets();
        const std::vector<float> best = run(targets.front());
        EXPECT_GT(*std::max_element(best.begin(), best.end()), 1e3f); // it read the heavy particles
        for (const std::string& target : targets) {
            const std::vector<float> other = run(target);
            ASSERT_EQ(other.size(), best.size());
            EXPECT_EQ(std::memcmp(other.data(), best.data(), best.size() * sizeof(float)), 0)
                << target << " against " << targets.front();
        }
        forceSimdTarget("");
    }
}

// A solid ball of 2 cm and a cloud of 2,000 particles of different weights and moves around it,
// splatted one by one into slot 0 of a grid laid over (-0.1, 0.1)^3 (not finished).
void splatACloud(HairVolumeGrid& grid)
{
    grid.setSolid([](const glm::vec3& p) { return glm::length(p) - 0.02f; });
    grid.setWeightBound(2000.0);
    for (int i = 0; i < 2000; ++i) {
        const float t = static_cast<float>(i);
        grid.splat(0, { 0.05f * std::sin(t * 0.37f), 0.05f * std::sin(t * 0.11f), 0.05f * std::cos(t * 0.23f) },
            1.0f + 0.5f * std::sin(t), { 0.001f * std::cos(t), 0.0005f, -0.002f * std::sin(t * 0.7f) });
    }
}

// A full row of sixteen read at once (eight lanes at a time, turned into the row's arrays by a
// transpose) gives each lane exactly what it reads alone, every one of its eight values; lanes
// outside the grid read zeros.
TEST(HairVolumeGrid, AFullTrilinearRowReadsWhatEachLaneReadsAlone)
{
    HairVolumeGrid grid;
    ASSERT_TRUE(grid.setBounds(glm::vec3(-0.1f), glm::vec3(0.1f)));
    splatACloud(grid);
    grid.finish(nullptr, 3000.0f);
    alignas(64) float x[16], y[16], z[16];
    for (int l = 0; l < 16; ++l) {
        x[l] = -0.04f + 0.0053f * static_cast<float>(l);
        y[l] = 0.003f * static_cast<float>(l % 5) - 0.01f;
        z[l] = 0.02f * std::sin(static_cast<float>(l));
    }
    x[6] = 0.5f; // outside
    HairVolumeGrid::SampleRow row;
    grid.sampleRow(x, y, z, row);
    for (int l = 0; l < 16; ++l) {
        HairVolumeGrid::SampleRow alone;
        grid.sampleRow(&x[l], &y[l], &z[l], alone, 1);
        const float* const rowFields[8]
            = { row.density, row.gradX, row.gradY, row.gradZ, row.momentumX, row.momentumY, row.momentumZ, row.hair };
        const float* const aloneFields[8] = { alone.density, alone.gradX, alone.gradY, alone.gradZ, alone.momentumX,
            alone.momentumY, alone.momentumZ, alone.hair };
        for (int f = 0; f < 8; ++f)
            EXPECT_EQ(rowFields[f][l], aloneFields[f][0]) << "lane " << l << ", value " << f;
    }
    EXPECT_EQ(row.density[6], 0.0f);
    EXPECT_GT(row.hair[8], 0.0f); // inside the hair
    EXPECT_NE(row.momentumZ[8], 0.0f);
}

// A row sampled every fourth lane (the level of detail of a dense groom): lanes 0, 4, 8, 12 and 15
// read what sample() reads there, the lanes between the linear blend of the two around them.
TEST(HairVolumeGrid, AStridedRowBlendsTheSamplesAroundEachLane)
{
    HairVolumeGrid grid;
    ASSERT_TRUE(grid.setBounds(glm::vec3(-0.1f), glm::vec3(0.1f)));
    grid.setWeightBound(2000.0);
    for (int i = 0; i < 2000; ++i) {
        const float t = static_cast<float>(i);
        grid.splat(0, { 0.03f * std::sin(t * 0.37f), 0.03f * std::sin(t * 0.11f), 0.03f * std::cos(t * 0.23f) }, 1.0f,
            { 0.001f, 0.0f, 0.0f });
    }
    grid.finish(nullptr);
    alignas(64) float x[16], y[16], z[16];
    for (int l = 0; l < 16; ++l) {
        x[l] = -0.03f + 0.004f * static_cast<float>(l);
        y[l] = 0.002f * static_cast<float>(l % 5);
        z[l] = 0.01f;
    }
    HairVolumeGrid::SampleRow row;
    grid.sampleRow(x, y, z, row, 16, 4);
    auto at = [&](int l) { return grid.sample({ x[l], y[l], z[l] }); };
    for (int l : { 0, 4, 8, 12, 15 }) {
        EXPECT_FLOAT_EQ(row.density[l], at(l).density) << "lane " << l;
        EXPECT_FLOAT_EQ(row.gradX[l], at(l).gradient.x) << "lane " << l;
    }
    EXPECT_GT(row.density[8], 1e5f); // inside the hair
    EXPECT_FLOAT_EQ(row.density[5], 0.75f * at(4).density + 0.25f * at(8).density);
    EXPECT_FLOAT_EQ(row.gradY[10], 0.5f * at(8).gradient.y + 0.5f * at(12).gradient.y);
    EXPECT_FLOAT_EQ(row.density[13], (2.0f * at(12).density + at(15).density) / 3.0f);
    EXPECT_NE(row.density[5], at(5).density); // not sampled there
}

// A dense groom's grid reads a row's sixteen nodes at once (HairVolumeGrid::nearestRow, a transpose
// in registers): each lane gets exactly what it reads alone, every one of the node's eight values;
// lanes outside the grid read zeros.
TEST(HairVolumeGrid, ANearestRowReadsWhatEachLaneReadsAlone)
{
    HairVolumeGrid grid;
    ASSERT_TRUE(grid.setBounds(
        glm::vec3(-0.1f), glm::vec3(0.1f), 1, HairVolumeGrid::kMaxNodes, HairVolumeGrid::Kernel::NearestSmoothed));
    splatACloud(grid);
    grid.finish(nullptr, 1e4f);
    alignas(64) float x[16], y[16], z[16];
    for (int l = 0; l < 16; ++l) {
        x[l] = -0.045f + 0.006f * static_cast<float>(l);
        y[l] = 0.007f * static_cast<float>(l % 5) - 0.01f;
        z[l] = l == 3 ? 5.0f : 0.004f * static_cast<float>(l % 3); // lane 3 outside the grid
    }
    auto expectLane = [&](const HairVolumeGrid::SampleRow& row, int l) {
        const HairVolumeGrid::Sample alone = grid.sample({ x[l], y[l], z[l] });
        EXPECT_EQ(row.density[l], alone.density) << "lane " << l;
        EXPECT_EQ(row.gradX[l], alone.gradient.x) << "lane " << l;
        EXPECT_EQ(row.gradY[l], alone.gradient.y) << "lane " << l;
        EXPECT_EQ(row.gradZ[l], alone.gradient.z) << "lane " << l;
        EXPECT_EQ(row.hair[l], alone.hair) << "lane " << l;
        if (alone.hair > 0.0f) {
            EXPECT_FLOAT_EQ(row.momentumX[l] / row.hair[l], alone.move.x) << "lane " << l;
            EXPECT_FLOAT_EQ(row.momentumY[l] / row.hair[l], alone.move.y) << "lane " << l;
            EXPECT_FLOAT_EQ(row.momentumZ[l] / row.hair[l], alone.move.z) << "lane " << l;
        }
    };
    HairVolumeGrid::SampleRow row;
    grid.sampleRow(x, y, z, row, 16, 1);
    for (int l = 0; l < 16; ++l)
        expectLane(row, l);
    EXPECT_EQ(row.density[3], 0.0f);
    EXPECT_EQ(row.hair[3], 0.0f);
    int inHair = 0;
    for (int l = 0; l < 16; ++l)
        inHair += row.hair[l] > 0.0f && row.gradX[l] != 0.0f;
    EXPECT_GE(inHair, 12); // the row runs through the hair: the values compared are not all zeros
    // Every fourth lane and the last: those read alone, the ones between blend them.
    grid.sampleRow(x, y, z, row, 16, 4);
    for (int l : { 0, 4, 8, 12, 15 })
        expectLane(row, l);
    EXPECT_FLOAT_EQ(row.density[6], 0.5f * row.density[4] + 0.5f * row.density[8]);
    EXPECT_FLOAT_EQ(row.momentumZ[13], (2.0f * row.momentumZ[12] + row.momentumZ[15]) / 3.0f);
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

TEST(Volume, OnByDefaultAtItsNaturalVolume)
{
    EXPECT_EQ(parameterInfo(Param::Volume).defaultValue, kNaturalVolume);
    EXPECT_EQ(ParameterValues{}.get(Param::Volume), kNaturalVolume);
}

TEST(Volume, DefaultGroomStandsOffTheScalpOnTop)
{
    float p90[2] = { 0, 0 };
    for (int on = 0; on < 2; ++on) {
        auto sim = makeSimulation(defaultStill(on ? kNaturalVolume : 0.0));
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

TEST(Volume, WetHairTakesLessRoom)
{
    float p90[2] = { 0, 0 };
    for (int wet = 0; wet < 2; ++wet) {
        auto sim = makeSimulation(defaultStill(kNaturalVolume));
        if (wet) {
            std::vector<std::uint64_t> keys;
            for (std::size_t w = 0; w < sim->groom().wispCount(); ++w)
                keys.push_back(sim->groom().strandIdentity(sim->groom().keyStrand[w]));
            sim->wet(keys, 1.0f);
        }
        run(*sim, 600);
        p90[wet] = percentile(topDistances(*sim), 0.9);
    }
    std::printf("top quarter, p90 from the scalp: dry %.1f mm, soaked %.1f mm\n", 1e3 * p90[0], 1e3 * p90[1]);
    EXPECT_LT(p90[1], 0.75f * p90[0]);
}

} // namespace

namespace {

TEST(Volume, SettledHairStaysStillAndFiniteAfterTenSeconds)
{
    auto sim = makeSimulation(defaultStill(kNaturalVolume));
    run(*sim, 600); // 10 s at 1/60 s
    std::size_t moving = 0, total = 0;
    for (int step = 0; step < 10; ++step) {
        const std::vector<glm::vec3> before = simulatedTips(*sim);
        sim->step();
        const std::vector<glm::vec3> after = simulatedTips(*sim);
        for (std::size_t i = 0; i < before.size(); ++i) {
            ASSERT_TRUE(std::isfinite(after[i].x + after[i].y + after[i].z));
            moving += glm::distance(before[i], after[i]) > 0.001f ? 1 : 0;
            ++total;
        }
    }
    const double share = static_cast<double>(moving) / static_cast<double>(total);
    std::printf("tips moving more than 1 mm per step after 10 s: %.2f %%\n", 100.0 * share);
    EXPECT_LT(share, 0.01);
    EXPECT_EQ(sim->solver().strandsReset(), 0u);
}

// The settling cases of SettlingTest.cpp, with volume on: hair resting on hair must not bounce.
struct SettleCase {
    int substeps, segments;
    bool curly;
};
class VolumeSettling : public testing::TestWithParam<SettleCase> { };
TEST_P(VolumeSettling, FewerThanOnePercentOfTipsStillMoveAfterTenSeconds)
{
    const SettleCase k = GetParam();
    ParameterValues v = testParameters();
    v.set(Param::Volume, kNaturalVolume);
    v.set(Param::Substeps, k.substeps);
    v.set(Param::Segments, k.segments);
    if (k.curly) {
        v.set(Param::CurlRadius, 0.008);
        v.set(Param::CurlTurns, 25.0);
    }
    auto sim = makeSimulation(v);
    run(*sim, 600);
    const std::vector<glm::vec3> before = simulatedTips(*sim);
    sim->step();
    const std::vector<glm::vec3> after = simulatedTips(*sim);
    std::size_t moving = 0;
    for (std::size_t i = 0; i < before.size(); ++i)
        moving += glm::distance(before[i], after[i]) > 0.001f ? 1 : 0;
    const double share = static_cast<double>(moving) / static_cast<double>(before.size());
    std::printf("volume on, %s, %d substeps, %d segments: %.1f %% of tips still move > 1 mm a step after 10 s\n",
        k.curly ? "curly" : "straight", k.substeps, k.segments, 100.0 * share);
    EXPECT_LT(share, 0.01);
}
INSTANTIATE_TEST_SUITE_P(SubstepsSegmentsCurl, VolumeSettling,
    testing::Values(SettleCase{ 1, 8, false }, SettleCase{ 1, 40, false }, SettleCase{ 8, 40, false },
        SettleCase{ 4, 15, false }, SettleCase{ 2, 40, true }));

TEST(Volume, NoNonFiniteOrResetAtTheExtremes)
{
    struct Case {
        double volume, friction, gravity, wind, timeStep;
        int substeps;
    };
    for (const Case k : { Case{ 1.0, 1.0, 100.0, 100.0, 0.1, 1 }, Case{ 1.0, 0.0, -100.0, 0.0, 0.1, 1 },
             Case{ 1.0, 1.0, 9.81, 50.0, 1.0 / 60.0, 32 }, Case{ 0.001, 0.5, 9.81, 0.0, 0.001, 1 } }) {
        ParameterValues v = testParameters();
        v.set(Param::Volume, k.volume);
        v.set(Param::HairFriction, k.friction);
        v.set(Param::Gravity, k.gravity);
        v.set(Param::WindSpeed, k.wind);
        v.set(Param::Turbulence, 2.0);
        v.set(Param::TimeStep, k.timeStep);
        v.set(Param::Substeps, k.substeps);
        auto sim = makeSimulation(v);
        run(*sim, 40);
        std::vector<glm::vec3> p;
        sim->copySimulated(p);
        for (const glm::vec3& x : p)
            ASSERT_TRUE(std::isfinite(x.x + x.y + x.z)) << "volume " << k.volume << " gravity " << k.gravity;
        // A reset strand is one that went non-finite or flew off: none may.
        EXPECT_EQ(sim->solver().strandsReset(), 0u)
            << "volume " << k.volume << " gravity " << k.gravity << " wind " << k.wind;
    }
}

TEST(Volume, ABrokenStrandIsResetAndSpreadsNothingNonFinite)
{
    ParameterValues v = testParameters();
    v.set(Param::Volume, 1.0);
    v.set(Param::HairFriction, 1.0);
    auto sim = makeSimulation(v, 2);
    run(*sim, 20);
    sim->solver().moveParticle(3, 5, glm::vec3(NAN));
    sim->step();
    EXPECT_EQ(sim->solver().strandsReset(), 1u); // only the broken one
    run(*sim, 5);
    std::vector<glm::vec3> p;
    sim->copySimulated(p);
    for (const glm::vec3& x : p)
        ASSERT_TRUE(std::isfinite(x.x + x.y + x.z));
    EXPECT_EQ(sim->solver().strandsReset(), 1u);
}

TEST(Volume, SameBitsWithOneAndThreeThreads)
{
    ParameterValues v = testParameters();
    v.set(Param::WindSpeed, 3.0);
    v.set(Param::Turbulence, 0.6);
    v.set(Param::Volume, 0.8);
    v.set(Param::HairFriction, 0.5);
    std::vector<glm::vec3> p[2];
    for (int k = 0; k < 2; ++k) {
        auto sim = makeSimulation(v, k == 0 ? 1 : 3);
        // A moving head: the grid follows it.
        for (int i = 0; i < 60; ++i) {
            sim->solver().setHeadTransform(glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0),
                glm::vec4(0, 0, 1, 0), glm::vec4(0.002f * static_cast<float>(i), 0.0f, 0.0f, 1.0f)));
            sim->step();
        }
        sim->copySimulated(p[k]);
        ASSERT_NE(sim->solver().volumeGrid(), nullptr);
    }
    ASSERT_EQ(p[0].size(), p[1].size());
    EXPECT_EQ(std::memcmp(p[0].data(), p[1].data(), p[0].size() * sizeof(glm::vec3)), 0);
}

// The grid is laid every substep at the default two substeps at 60 Hz, but only once a step for
// many short substeps (its pass was most of the cost of a heavy scene's 32 substeps).
TEST(Volume, GridIsLaidEverySubstepByDefaultAndOnceAStepForShortSubsteps)
{
    ParameterValues v = testParameters();
    v.set(Param::Volume, kNaturalVolume);
    v.set(Param::Substeps, 2.0);
    v.set(Param::TimeStep, 1.0 / 60.0);
    auto twoSubsteps = makeSimulation(v, 1);
    for (int i = 0; i < 3; ++i)
        twoSubsteps->step();
    EXPECT_EQ(twoSubsteps->solver().volumePasses(), 6u);
    v.set(Param::Substeps, 32.0);
    v.set(Param::TimeStep, 0.001);
    auto shortSubsteps = makeSimulation(v, 1);
    for (int i = 0; i < 3; ++i)
        shortSubsteps->step();
    EXPECT_EQ(shortSubsteps->solver().volumePasses(), 3u);
    // 8 substeps at 60 Hz (2.1 ms each): every fourth, 1/120 s apart.
    v.set(Param::Substeps, 8.0);
    v.set(Param::TimeStep, 1.0 / 60.0);
    auto eightSubsteps = makeSimulation(v, 1);
    for (int i = 0; i < 3; ++i)
        eightSubsteps->step();
    EXPECT_EQ(eightSubsteps->solver().volumePasses(), 6u);
}

// Two locks on a floor (a sphere of 1 m radius), the top one laid across the bottom one a little
// above it. With volume they stay apart where they cross; with volume 0 the top one falls through
// onto the floor, into the other.
struct CrossResult {
    double shareApart = 0.0; // of the top lock's particles over the bottom lock
    std::size_t over = 0;
};
CrossResult crossLocks(float volume)
{
    constexpr int kStrands = 16, kPoints = 16;
    // The floor is a sphere of 100 m: flat within 0.05 mm under the locks. (On one of 1 m the top lock,
    // pushed up by the bottom one, slid down the curve off it, more or fewer of its particles by
    // rounding: 22 on main, 14 with the trilinear read.)
    constexpr float kLength = 0.2f, kWidth = 0.04f, kFloor = 100.0f;
    HairCurves rest;
    for (int lock = 0; lock < 2; ++lock)
        for (int s = 0; s < kStrands; ++s) {
            const float across = -0.5f * kWidth + kWidth * static_cast<float>(s) / (kStrands - 1);
            auto points = rest.strandForWrite(rest.addStrand(kPoints));
            for (int j = 0; j < kPoints; ++j) {
                const float along = -0.5f * kLength + kLength * static_cast<float>(j) / (kPoints - 1);
                // The bottom lock runs along X on the floor; the top one along Z, 6 mm higher.
                const glm::vec3 flat = lock == 0 ? glm::vec3(along, 0.0f, across) : glm::vec3(across, 0.0f, along);
                points[j] = flat + glm::vec3(0.0f, kFloor + 0.004f + (lock == 1 ? 0.006f : 0.0f), 0.0f);
            }
        }
    Solver solver(2);
    EXPECT_EQ(solver.setStrands(rest), "");
    SolverSettings s;
    s.substeps = 2;
    s.stiffness = 0.05f;
    s.dampingPerSecond = 2.0f;
    s.friction = 0.3f;
    s.hairOffsetMetres = 0.002f;
    s.volume = volume;
    s.hairFriction = 0.2f;
    EXPECT_EQ(solver.setSettings(s), "");
    solver.setCapsules({ Capsule{ { 0, 0, 0 }, { 0, 0, 0 }, kFloor } });
    // Each key stands for 12 drawn strands growing at 8 strands/cm², as in the default groom.
    const std::vector<float> drawn(2 * kStrands, 12.0f);
    EXPECT_EQ(solver.setStrandVolume(drawn, 2 * kStrands * 12 / 8e4f), "");
    for (int i = 0; i < 300; ++i)
        solver.step();
    std::vector<glm::vec3> p;
    solver.copyPositions(p);
    const std::size_t half = p.size() / 2;
    CrossResult r;
    std::size_t apart = 0;
    for (std::size_t i = half; i < p.size(); ++i) {
        if (std::abs(p[i].x) > 0.5f * kLength || std::abs(p[i].z) > 0.5f * kWidth)
            continue; // not over the bottom lock
        float nearest = INFINITY;
        for (std::size_t k = 0; k < half; ++k) {
            if (k % kPoints == kPoints - 1)
                continue;
            const glm::vec3 a = p[k], b = p[k + 1]; // the bottom lock's segments
            const float t = std::clamp(glm::dot(p[i] - a, b - a) / glm::dot(b - a, b - a), 0.0f, 1.0f);
            nearest = std::min(nearest, glm::distance(p[i], a + t * (b - a)));
        }
        ++r.over;
        apart += nearest >= s.hairOffsetMetres ? 1 : 0;
    }
    r.shareApart = r.over ? static_cast<double>(apart) / static_cast<double>(r.over) : 0.0;
    return r;
}

// The hair radius here is the hair offset, 2 mm: what the solver keeps between a hair's centre
// line and the skin.
TEST(Volume, ALockLaidAcrossAnotherRestsOnIt)
{
    const CrossResult with = crossLocks(1.0f), without = crossLocks(0.0f);
    std::printf("top lock's particles over the bottom lock at least 2 mm from it: volume 1 %.1f %% of %zu, volume 0 "
                "%.1f %% of %zu\n",
        100.0 * with.shareApart, with.over, 100.0 * without.shareApart, without.over);
    // (How many of the top lock's particles lie over the bottom one's footprint depends on rounding:
    // its rows at the footprint's edge slide in or out. 16 is one a strand.)
    ASSERT_GE(with.over, 16u);
    EXPECT_GE(with.shareApart, 0.95);
    EXPECT_LT(without.shareApart, 0.5);
}

} // namespace

namespace {

// A square patch of side x side strands of `points` particles, `spacing` apart, hanging along -Y.
HairCurves densePatch(int side = 16, int points = 10, float spacing = 0.0005f, float segment = 0.012f)
{
    HairCurves rest;
    for (int row = 0; row < side; ++row)
        for (int lane = 0; lane < side; ++lane) {
            auto p = rest.strandForWrite(rest.addStrand(static_cast<std::size_t>(points)));
            for (int j = 0; j < points; ++j)
                p[static_cast<std::size_t>(j)] = glm::vec3(spacing * static_cast<float>(lane),
                    -segment * static_cast<float>(j), spacing * static_cast<float>(row));
        }
    return rest;
}

struct PatchRun {
    std::vector<glm::vec3> positions;
    int stride = 0; // Solver::volumeStrideOfStrand(0) at the end
    int rowsPerSample = 0; // Solver::volumeRowsPerSampleOfStrand(0) at the end
    double gridWeight = 0.0; // the grid's total weight at its last pass
    HairVolumeGrid::Kernel kernel = HairVolumeGrid::Kernel::Trilinear;
};

PatchRun runPatch(const HairCurves& rest, float volume, int threads, int substeps, int steps)
{
    Solver solver(threads);
    EXPECT_EQ(solver.setStrands(rest), "");
    SolverSettings s;
    s.substeps = substeps;
    s.dampingPerSecond = 2.0f;
    s.volume = volume;
    s.hairFriction = 0.3f;
    EXPECT_EQ(solver.setSettings(s), "");
    for (int i = 0; i < steps; ++i)
        solver.step();
    PatchRun run;
    run.stride = solver.volumeStrideOfStrand(0);
    run.rowsPerSample = solver.volumeRowsPerSampleOfStrand(0);
    if (solver.volumeGrid()) {
        run.kernel = solver.volumeGrid()->kernel();
        run.gridWeight = solver.volumeGrid()->totalWeight();
    }
    solver.copyPositions(run.positions);
    return run;
}

std::vector<glm::vec3> settledPatch(float volume, int threads, int* stride = nullptr)
{
    PatchRun run = runPatch(densePatch(), volume, threads, 2, 60);
    if (stride)
        *stride = run.stride;
    return std::move(run.positions);
}

// How far apart the tips (every `points`-th particle) lie along x; each finite.
float tipSpanX(const std::vector<glm::vec3>& p, std::size_t points)
{
    float lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = points - 1; i < p.size(); i += points) {
        EXPECT_TRUE(std::isfinite(p[i].x + p[i].y + p[i].z));
        lo = std::min(lo, p[i].x);
        hi = std::max(hi, p[i].x);
    }
    return hi - lo;
}

// A dense patch (strands 0.5 mm apart, rows of 16 side by side): the grid splats and samples every
// few strands (Solver::volumeSplat's level of detail), keeps the same bits on any thread count with
// the splat done at the end of each block's substeps, and spreads the hair as much as without the
// level of detail.
TEST(Volume, ADensePatchSplatsEveryFewStrandsWithTheSameBitsOnAnyThreads)
{
    int stride = 0;
    const std::vector<glm::vec3> one = settledPatch(1.0f, 1, &stride), three = settledPatch(1.0f, 3);
    EXPECT_GE(stride, 4); // 0.5 mm apart in 8 mm cells
    EXPECT_EQ(runPatch(densePatch(), 1.0f, 1, 2, 2).rowsPerSample, 1); // the trilinear grid: row by row
    ASSERT_EQ(one.size(), three.size());
    EXPECT_EQ(std::memcmp(one.data(), three.data(), one.size() * sizeof(glm::vec3)), 0);
    // The tips spread apart where at volume 0 they hang in a 7.5 mm square.
    // Measured: 8.9 mm (8.8 mm with every strand splatting and sampled, stride 1).
    const float still = tipSpanX(settledPatch(0.0f, 1), 10), spread = tipSpanX(one, 10);
    EXPECT_NEAR(still, 0.0075f, 0.0005f);
    EXPECT_GT(spread, 1.1f * still);
}

// Above 250,000 particles (groom-1m) the grid is coarser and each particle meets only its nearest
// node: a patch of 128 x 128 strands of 16 particles, 1 mm apart, keeps the same bits on any thread
// count and still spreads where at volume 0 it hangs straight.
PatchRun denseDrape(float volume, int threads)
{
    return runPatch(densePatch(128, 16, 0.001f, 0.01f), volume, threads, 1, 12);
}

TEST(Volume, ADenseGroomMeetsItsNearestNodeWithTheSameBitsOnAnyThreads)
{
    const PatchRun one = denseDrape(1.0f, 1), three = denseDrape(1.0f, 3);
    EXPECT_EQ(one.kernel, HairVolumeGrid::Kernel::NearestSmoothed);
    ASSERT_EQ(one.positions.size(), 128u * 128u * 16u);
    ASSERT_EQ(one.positions.size(), three.positions.size());
    EXPECT_EQ(std::memcmp(one.positions.data(), three.positions.data(), one.positions.size() * sizeof(glm::vec3)), 0);
    // The tips of the patch's outer strands: pushed outward from the dense middle.
    const float hanging = tipSpanX(denseDrape(0.0f, 1).positions, 16), spread = tipSpanX(one.positions, 16);
    std::printf("dense drape, tips across x after 12 steps: %.1f mm at volume 0, %.1f mm at volume 1\n", 1e3 * hanging,
        1e3 * spread);
    EXPECT_NEAR(hanging, 0.127f, 0.002f);
    EXPECT_GT(spread, 1.05f * hanging);
}

// A dense groom's splat and read run in registers, per SIMD target, with another transpose and
// blend on targets without AVX-512 (HairVolumeGridNearest-inl.h): every target this CPU runs gives
// the best target's bits.
TEST(Volume, ADenseGroomGivesTheSameBitsOnEverySimdTarget)
{
    const std::vector<std::string> targets = availableSimdTargets();
    const PatchRun best = denseDrape(1.0f, 2);
    EXPECT_EQ(best.kernel, HairVolumeGrid::Kernel::NearestSmoothed);
    for (std::size_t k = 1; k < targets.size(); ++k) {
        ASSERT_EQ(forceSimdTarget(targets[k]), "");
        const PatchRun run = denseDrape(1.0f, 2);
        ASSERT_EQ(forceSimdTarget(""), "");
        ASSERT_EQ(run.positions.size(), best.positions.size());
        EXPECT_EQ(std::memcmp(run.positions.data(), best.positions.data(), run.positions.size() * sizeof(glm::vec3)), 0)
            << targets[k];
    }
}

// The dense patch (Kernel::NearestSmoothed, its grid laid every other step at 60 Hz,
// kVolumeDenseRefreshSeconds, read every step) after 10 s: the share of its tips still moving more
// than 1 mm a step, over ten steps (five of the grid's passes); none is reset. The grid keeps a few
// of the patch's tips rocking (none at volume 0): measured 2.3 % with the grid laid every step
// (before kVolumeDenseRefreshSeconds), 2.6 % every other step (2.0 % with the stiffness capped as
// for the trilinear grid, kVolumeStableShare, which barely spreads the drape), 18.7 % when each
// block read it only once a pass with the whole interval's impulse (the push, which holds hair up
// against gravity, then comes in kicks: a sawtooth of about g dt² a step). The bar is against that.
double denseTipsMoving(float volume, std::uint64_t* passes = nullptr)
{
    Solver solver(2);
    EXPECT_EQ(solver.setStrands(densePatch(128, 16, 0.001f, 0.01f)), "");
    SolverSettings s;
    s.substeps = 1;
    s.dampingPerSecond = 2.0f;
    s.volume = volume;
    s.hairFriction = 0.3f;
    EXPECT_EQ(solver.setSettings(s), "");
    for (int i = 0; i < 600; ++i)
        solver.step();
    if (volume > 0.0f) {
        EXPECT_NE(solver.volumeGrid(), nullptr);
        if (solver.volumeGrid()) {
            EXPECT_EQ(solver.volumeGrid()->kernel(), HairVolumeGrid::Kernel::NearestSmoothed);
        }
    }
    std::size_t moving = 0, total = 0;
    std::vector<glm::vec3> before, after;
    solver.copyPositions(before);
    for (int step = 0; step < 10; ++step) {
        solver.step();
        solver.copyPositions(after);
        for (std::size_t i = 15; i < after.size(); i += 16) {
            EXPECT_TRUE(std::isfinite(after[i].x + after[i].y + after[i].z));
            moving += glm::distance(before[i], after[i]) > 0.001f ? 1 : 0;
            ++total;
        }
        std::swap(before, after);
    }
    EXPECT_EQ(solver.strandsReset(), 0u);
    if (passes)
        *passes = solver.volumePasses();
    return static_cast<double>(moving) / static_cast<double>(total);
}

TEST(Volume, ADenseGroomLaidEveryOtherStepSettles)
{
    std::uint64_t passes = 0;
    const double still = denseTipsMoving(0.0f), volume = denseTipsMoving(1.0f, &passes);
    EXPECT_EQ(passes, 305u); // 610 steps of one substep at 60 Hz: every other step
    std::printf("dense patch, tips moving more than 1 mm a step after 10 s: %.2f %% at volume 0, %.2f %% at volume 1\n",
        100.0 * still, 100.0 * volume);
    EXPECT_LT(volume, 0.05);
}

// The dense patch on a head that turns and moves every step: the grid, laid every other step in head
// space, is laid again from a sweep when the head moved since the blocks splatted (Solver::step),
// and the bits stay the same on any thread count.
std::vector<glm::vec3> denseOnAMovingHead(int threads, std::uint64_t* passes)
{
    Solver solver(threads);
    EXPECT_EQ(solver.setStrands(densePatch(128, 16, 0.001f, 0.01f)), "");
    SolverSettings s;
    s.substeps = 1;
    s.dampingPerSecond = 2.0f;
    s.volume = 1.0f;
    s.hairFriction = 0.3f;
    EXPECT_EQ(solver.setSettings(s), "");
    for (int step = 0; step < 12; ++step) {
        const float angle = 0.02f * static_cast<float>(step);
        glm::mat4 head(1.0f);
        head[0] = glm::vec4(std::cos(angle), 0.0f, -std::sin(angle), 0.0f);
        head[2] = glm::vec4(std::sin(angle), 0.0f, std::cos(angle), 0.0f);
        head[3] = glm::vec4(0.002f * static_cast<float>(step), 0.0f, 0.0f, 1.0f);
        solver.setHeadTransform(head);
        solver.step();
    }
    *passes = solver.volumePasses();
    std::vector<glm::vec3> p;
    solver.copyPositions(p);
    return p;
}

TEST(Volume, ADenseGroomOnAMovingHeadKeepsTheSameBitsOnAnyThreads)
{
    std::uint64_t passesOne = 0, passesThree = 0;
    const std::vector<glm::vec3> one = denseOnAMovingHead(1, &passesOne), three = denseOnAMovingHead(3, &passesThree);
    EXPECT_EQ(passesOne, 6u);
    EXPECT_EQ(passesThree, 6u);
    ASSERT_EQ(one.size(), three.size());
    for (const glm::vec3& p : one)
        ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
    EXPECT_EQ(std::memcmp(one.data(), three.data(), one.size() * sizeof(glm::vec3)), 0);
}

// A dense groom splats and samples its rows a few at a time, at their centroid, with the weight of
// all of them (Solver::volumeSplat): as many as span at most three cells along the strand. The
// 128 x 128 patch of 16 particles lays 8.1 mm cells: its 10 mm segments go two by two, 5 mm ones
// four by four; either way the grid holds every particle's weight (a strand's length over its
// segments, for each of its 16 particles).
TEST(Volume, ADenseGroomSplatsItsRowsAFewAtATimeWithTheirWholeWeight)
{
    for (const float segment : { 0.01f, 0.005f }) {
        const PatchRun run = runPatch(densePatch(128, 16, 0.001f, segment), 1.0f, 2, 1, 3);
        EXPECT_EQ(run.kernel, HairVolumeGrid::Kernel::NearestSmoothed);
        EXPECT_EQ(run.rowsPerSample, segment > 0.008f ? 2 : 4) << segment;
        const double expected = 128.0 * 128.0 * 16.0 * segment;
        EXPECT_NEAR(run.gridWeight, expected, 1e-4 * expected) << segment;
        for (const glm::vec3& p : run.positions)
            ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
    }
}

} // namespace
