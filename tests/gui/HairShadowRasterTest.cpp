// The deep opacity map's hair passes on the CPU (widgets/HairShadowRaster.h): which texels a strand
// darkens, at which depth, into which layers, and that threads, order and hostile points change
// nothing or draw nothing.
#include "widgets/HairShadowRaster.h"

#include "sim/util/ThreadPool.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace wisp {
namespace {

constexpr int kPixels = 32;
constexpr float kFar = 1e6f;

// A light looking down -z at the square [-1, 1]^2 (world x, y map to the texels), metres from the
// light = 10 - z; points with z in (-10, 10) lie between its planes.
ShadowRasterInput lightFromAbove(std::span<const glm::vec4> points, std::span<const std::uint32_t> offsets)
{
    ShadowRasterInput input;
    input.points = points;
    input.strandOffsets = offsets;
    input.lightViewProjection = glm::mat4(1.0f);
    input.lightViewProjection[2][2] = -0.1f; // clip z = -z / 10
    input.worldToShadow = glm::mat4(1.0f);
    input.worldToShadow[2][2] = -1.0f;
    input.worldToShadow[3][2] = 10.0f;
    input.pixels = kPixels;
    input.layerMetres = glm::vec4(0.1f, 0.3f, 0.6f, 1.0f);
    input.strandOpacity = 0.25f;
    return input;
}

// World x or y of texel i's centre.
float centre(int i)
{
    return (static_cast<float>(i) + 0.5f) / kPixels * 2.0f - 1.0f;
}

struct Maps {
    std::vector<glm::vec2> depth = std::vector<glm::vec2>(kPixels * kPixels, glm::vec2(kFar));
    std::vector<glm::vec4> opacity = std::vector<glm::vec4>(kPixels * kPixels, glm::vec4(-1.0f));
    glm::vec2& at(int x, int y) { return depth[static_cast<std::size_t>(y) * kPixels + x]; }
    glm::vec4& layers(int x, int y) { return opacity[static_cast<std::size_t>(y) * kPixels + x]; }
};

TEST(HairShadowRaster, AStrandSetsTheNearestDepthAndItsOwnOpacityInEveryLayerAlongItsTexels)
{
    // Along x from texel 4's centre to texel 20's at row 10, at z = 8: 2 m from the light.
    const std::vector<glm::vec4> points{ { centre(4), centre(10), 8.0f, 1.0f },
        { centre(20), centre(10), 8.0f, 1.0f } };
    const std::vector<std::uint32_t> offsets{ 0, 2 };
    Maps maps;
    drawShadowHair(lightFromAbove(points, offsets), maps.depth, maps.opacity, nullptr);
    for (int x = 0; x < kPixels; ++x)
        for (int y = 0; y < kPixels; ++y) {
            const bool on = y == 10 && x >= 4 && x < 20; // [first centre, last centre)
            EXPECT_FLOAT_EQ(maps.at(x, y).x, on ? 2.0f : kFar) << x << "," << y;
            EXPECT_FLOAT_EQ(maps.at(x, y).y, kFar); // the head's, untouched
            // At its own nearest depth: behind = 0, in front of every layer's far end.
            EXPECT_EQ(maps.layers(x, y), on ? glm::vec4(0.25f) : glm::vec4(0.0f)) << x << "," << y;
        }
}

TEST(HairShadowRaster, ADeeperStrandFillsOnlyTheLayersThatEndBehindIt)
{
    // Two strands over the same texels: one at 2 m from the light, one 0.4 m deeper.
    const std::vector<glm::vec4> points{ { centre(2), centre(5), 8.0f, 1.0f }, { centre(30), centre(5), 8.0f, 1.0f },
        { centre(2), centre(5), 7.6f, 1.0f }, { centre(30), centre(5), 7.6f, 1.0f } };
    const std::vector<std::uint32_t> offsets{ 0, 2, 4 };
    Maps maps;
    drawShadowHair(lightFromAbove(points, offsets), maps.depth, maps.opacity, nullptr);
    EXPECT_NEAR(maps.at(15, 5).x, 2.0f, 1e-5f);
    // The deeper one lies 0.4 m behind: past the 0.1 and 0.3 m layers' ends, before 0.6 and 1.0.
    const glm::vec4 layers = maps.layers(15, 5);
    EXPECT_FLOAT_EQ(layers.x, 0.25f);
    EXPECT_FLOAT_EQ(layers.y, 0.25f);
    EXPECT_FLOAT_EQ(layers.z, 0.5f);
    EXPECT_FLOAT_EQ(layers.w, 0.5f);
}

TEST(HairShadowRaster, TheHeadsNearerDepthStaysAndSkippedOrHostileStrandsDrawNothing)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<glm::vec4> points{ { centre(1), centre(3), 8.0f, 1.0f }, { centre(30), centre(3), 8.0f, 1.0f }, // good
        { centre(1), centre(7), 8.0f, 0.0f }, { centre(30), centre(7), 8.0f, 0.0f }, // tagged: not drawn
        { nan, centre(9), 8.0f, 1.0f }, { centre(30), centre(9), 8.0f, 1.0f }, // non-finite
        { 1e30f, centre(11), 8.0f, 1.0f }, { -1e30f, centre(11), 8.0f, 1.0f }, // absurd, but a line
        { centre(1), centre(13), 50.0f, 1.0f }, { centre(30), centre(13), 50.0f, 1.0f } }; // beyond the light
    const std::vector<std::uint32_t> offsets{ 0, 2, 4, 6, 8, 10 };
    Maps maps;
    maps.at(10, 3) = glm::vec2(1.0f, 1.0f); // the head nearer than the hair there
    drawShadowHair(lightFromAbove(points, offsets), maps.depth, maps.opacity, nullptr);
    EXPECT_FLOAT_EQ(maps.at(10, 3).x, 1.0f);
    EXPECT_FLOAT_EQ(maps.at(11, 3).x, 2.0f);
    // 1 m behind the head's surface: past every layer's far end.
    EXPECT_EQ(maps.layers(10, 3), glm::vec4(0.0f, 0.0f, 0.0f, 0.0f));
    for (int x = 0; x < kPixels; ++x) {
        EXPECT_FLOAT_EQ(maps.at(x, 7).x, kFar) << x;
        EXPECT_FLOAT_EQ(maps.at(x, 9).x, kFar) << x;
        EXPECT_FLOAT_EQ(maps.at(x, 13).x, kFar) << x;
    }
    EXPECT_FLOAT_EQ(maps.at(16, 11).x, 2.0f); // across the whole map
    // Wrong-sized maps are left alone.
    std::vector<glm::vec2> small(10, glm::vec2(kFar));
    std::vector<glm::vec4> smallOpacity(10, glm::vec4(-1.0f));
    drawShadowHair(lightFromAbove(points, offsets), small, smallOpacity, nullptr);
    EXPECT_EQ(smallOpacity[0], glm::vec4(-1.0f));
}

TEST(HairShadowRaster, ThreadsGiveTheSameMapsAsOne)
{
    std::vector<glm::vec4> points;
    std::vector<std::uint32_t> offsets{ 0 };
    for (int s = 0; s < 300; ++s) {
        for (int k = 0; k < 8; ++k) {
            const float t = static_cast<float>(k) / 7.0f;
            points.emplace_back(std::sin(0.7f * s + 2.0f * t) * 0.9f, std::cos(0.3f * s + t) * 0.9f,
                8.0f - 0.5f * t - 0.001f * s, 1.0f);
        }
        offsets.push_back(static_cast<std::uint32_t>(points.size()));
    }
    Maps alone;
    Maps shared;
    drawShadowHair(lightFromAbove(points, offsets), alone.depth, alone.opacity, nullptr);
    ThreadPool pool(3);
    drawShadowHair(lightFromAbove(points, offsets), shared.depth, shared.opacity, &pool);
    int drawn = 0;
    for (std::size_t i = 0; i < alone.depth.size(); ++i) {
        EXPECT_EQ(alone.depth[i], shared.depth[i]) << i;
        for (int k = 0; k < 4; ++k) // sums of the same quarters in another order: exact
            EXPECT_EQ(alone.opacity[i][k], shared.opacity[i][k]) << i;
        drawn += alone.depth[i].x < kFar ? 1 : 0;
    }
    EXPECT_GT(drawn, 200);
}

} // namespace
} // namespace wisp
