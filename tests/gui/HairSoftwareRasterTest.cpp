// The hair's strands drawn on the CPU (widgets/HairSoftwareRaster.h): how much ink a strand leaves
// and where, that the backdrop hides what is behind it, that later strands lie over earlier ones,
// that the threads change nothing visible, and that hostile samples draw nothing instead of crashing.
#include "widgets/HairSoftwareRaster.h"

#include "sim/util/ThreadPool.h"

#include <glm/vec3.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace wisp {
namespace {

constexpr int kSize = 64;

// A sample at pixel (x, y) of a kSize x kSize target, window depth 0.5, drawn with colour (r, g, b)
// and coverage a; halfExtent 1 is a line.
HairRasterSample at(float x, float y, glm::vec3 rgb, float a, float halfExtent = 1.0f, float w = 1.0f)
{
    HairRasterSample s;
    s.clip = glm::vec4((x / kSize * 2.0f - 1.0f) * w, (y / kSize * 2.0f - 1.0f) * w, 0.0f, w);
    s.colour = glm::vec4(rgb, a);
    s.side = glm::vec4(0.0f, 0.0f, halfExtent, 0.0f);
    return s;
}

struct Drawn {
    std::vector<std::uint8_t> rgba; // whole target
    float alpha(int x, int y) const { return rgba[4 * (static_cast<std::size_t>(y) * kSize + x) + 3] / 255.0f; }
    int channel(int x, int y, int c) const { return rgba[4 * (static_cast<std::size_t>(y) * kSize + x) + c]; }
};

Drawn draw(const std::vector<HairRasterSample>& samples, const std::vector<std::uint32_t>& ends,
    const std::vector<float>& depth = {}, ThreadPool* pool = nullptr)
{
    HairRasterInput input;
    input.samples = samples;
    input.strandEnds = ends;
    input.width = kSize;
    input.height = kSize;
    input.region = PixelRect{ 0, 0, kSize, kSize };
    input.depth = depth;
    HairSoftwareRaster raster;
    const std::span<const std::uint8_t> image = raster.draw(input, pool);
    return Drawn{ std::vector<std::uint8_t>(image.begin(), image.end()) };
}

TEST(HairSoftwareRaster, ALevelLineLeavesItsCoverageInEachColumnItCrossesAndNoneBeyond)
{
    // From x = 10.2 to 40.7 at y = 20.3: columns whose centres lie in [10.2, 40.7), 10 .. 40.
    const Drawn image
        = draw({ at(10.2f, 20.3f, glm::vec3(1.0f), 0.6f), at(40.7f, 20.3f, glm::vec3(1.0f), 0.6f) }, { 2 });
    for (int x = 0; x < kSize; ++x) {
        float column = 0.0f;
        for (int y = 0; y < kSize; ++y) {
            column += image.alpha(x, y);
            if (y != 19 && y != 20) {
                EXPECT_EQ(image.alpha(x, y), 0.0f) << x << "," << y; // only the two rows it straddles
            }
        }
        if (x >= 10 && x <= 40) {
            EXPECT_NEAR(column, 0.6f, 1.5f / 255.0f) << x;
        } else {
            EXPECT_EQ(column, 0.0f) << x;
        }
    }
    // The centre line at 20.3 lies 0.8 past row 19's centre (19.5) and 0.2 short of row 20's: row 20
    // takes 0.8 of the coverage, row 19 0.2.
    EXPECT_NEAR(image.alpha(25, 20), 0.6f * 0.8f, 1.0f / 255.0f);
    EXPECT_NEAR(image.alpha(25, 19), 0.6f * 0.2f, 1.0f / 255.0f);
}

TEST(HairSoftwareRaster, ASlantedLineLeavesAsMuchInkPerLengthAsALevelOne)
{
    // 45 degrees: each column holds 1/cos = sqrt(2) times the coverage, over sqrt(2) times fewer
    // columns per unit of length.
    const Drawn slanted
        = draw({ at(10.0f, 10.0f, glm::vec3(1.0f), 0.3f), at(40.0f, 40.0f, glm::vec3(1.0f), 0.3f) }, { 2 });
    float ink = 0.0f;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            ink += slanted.alpha(x, y);
    const float length = std::sqrt(2.0f) * 30.0f;
    EXPECT_NEAR(ink / length, 0.3f, 0.01f);
}

TEST(HairSoftwareRaster, AStripsSegmentsMeetWithoutAGapOrAColumnDrawnTwice)
{
    // Five segments along x with uneven lengths, at a fractional height.
    std::vector<HairRasterSample> strip;
    for (const float x : { 5.3f, 9.9f, 10.1f, 21.6f, 22.0f, 50.45f })
        strip.push_back(at(x, 30.6f, glm::vec3(1.0f), 0.5f));
    const Drawn image = draw(strip, { static_cast<std::uint32_t>(strip.size()) });
    for (int x = 5; x <= 49; ++x) {
        float column = 0.0f;
        for (int y = 0; y < kSize; ++y)
            column += image.alpha(x, y);
        EXPECT_NEAR(column, 0.5f, 1.5f / 255.0f) << x;
    }
}

TEST(HairSoftwareRaster, ARibbonCoversItsDrawnWidthAcross)
{
    // halfExtent 2.5: a ribbon 4 pixels wide (its 1-pixel antialiasing skirt included in the extent).
    const Drawn image
        = draw({ at(10.0f, 32.0f, glm::vec3(1.0f), 0.2f, 2.5f), at(50.0f, 32.0f, glm::vec3(1.0f), 0.2f, 2.5f) }, { 2 });
    for (int x = 12; x < 48; ++x) {
        float column = 0.0f;
        int touched = 0;
        for (int y = 0; y < kSize; ++y) {
            column += image.alpha(x, y);
            touched += image.alpha(x, y) > 0.0f ? 1 : 0;
        }
        EXPECT_NEAR(column, 0.2f * 4.0f, 3.0f / 255.0f) << x;
        EXPECT_LE(touched, 5) << x;
    }
}

TEST(HairSoftwareRaster, TheBackdropHidesWhatIsBehindIt)
{
    // The left half of the target has a backdrop at depth 0.3 (nearer than the hair's 0.5), the
    // right half at 0.9.
    std::vector<float> depth(kSize * kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            depth[static_cast<std::size_t>(y) * kSize + x] = x < 32 ? 0.3f : 0.9f;
    const Drawn image
        = draw({ at(4.0f, 20.5f, glm::vec3(1.0f), 1.0f), at(60.0f, 20.5f, glm::vec3(1.0f), 1.0f) }, { 2 }, depth);
    EXPECT_EQ(image.alpha(20, 20), 0.0f);
    EXPECT_EQ(image.alpha(31, 20), 0.0f);
    EXPECT_NEAR(image.alpha(32, 20), 1.0f, 1.0f / 255.0f);
    EXPECT_NEAR(image.alpha(50, 20), 1.0f, 1.0f / 255.0f);
}

TEST(HairSoftwareRaster, LaterStrandsLieOverEarlierOnesPremultiplied)
{
    // A red strand, then a green one over the same pixels, the green at 60 % coverage.
    const Drawn image
        = draw({ at(10.0f, 20.5f, glm::vec3(1, 0, 0), 1.0f), at(40.0f, 20.5f, glm::vec3(1, 0, 0), 1.0f),
                   at(10.0f, 20.5f, glm::vec3(0, 1, 0), 0.6f), at(40.0f, 20.5f, glm::vec3(0, 1, 0), 0.6f) },
            { 2, 4 });
    // Centre line on row 20's centre: row 20 takes it all.
    EXPECT_NEAR(image.channel(20, 20, 0), 0.4 * 255, 1.0); // red left under 40 %
    EXPECT_NEAR(image.channel(20, 20, 1), 0.6 * 255, 1.0);
    EXPECT_EQ(image.channel(20, 20, 3), 255);
}

TEST(HairSoftwareRaster, ThreadsDrawTheSameImageToTheLastLevel)
{
    // Many overlapping translucent strands in several colours, drawn by one thread and by four.
    std::vector<HairRasterSample> samples;
    std::vector<std::uint32_t> ends;
    for (int s = 0; s < 400; ++s) {
        const float phase = 0.37f * static_cast<float>(s);
        const glm::vec3 colour(0.5f + 0.5f * std::sin(phase), 0.5f + 0.5f * std::cos(phase), 0.3f);
        for (int k = 0; k < 12; ++k) {
            const float t = static_cast<float>(k) / 11.0f;
            samples.push_back(at(8.0f + 48.0f * t, 8.0f + 48.0f * std::fmod(0.13f * s + 0.5f * t * t, 1.0f), colour,
                0.15f + 0.1f * std::sin(phase * 3.0f)));
        }
        ends.push_back(static_cast<std::uint32_t>(samples.size()));
    }
    const Drawn alone = draw(samples, ends);
    ThreadPool pool(4);
    const Drawn shared = draw(samples, ends, {}, &pool);
    int inked = 0;
    for (std::size_t i = 0; i < alone.rgba.size(); ++i) {
        EXPECT_LE(std::abs(int(alone.rgba[i]) - int(shared.rgba[i])), 1) << i;
        inked += i % 4 == 3 && alone.rgba[i] > 0 ? 1 : 0;
    }
    EXPECT_GT(inked, kSize * kSize / 2);
}

TEST(HairSoftwareRaster, TheNearPlaneCutsAStrandThatCrossesIt)
{
    // From a point in front of the camera (w = 1) to one behind it (w = -1, z < -w): the part in
    // front is drawn up to where the strand crosses the near plane, the rest not at all.
    HairRasterSample front = at(10.0f, 32.5f, glm::vec3(1.0f), 1.0f);
    front.clip.z = 0.5f; // z + w = 1.5
    HairRasterSample behind = front;
    behind.clip = glm::vec4(0.9f, 0.0156f, -2.5f, 1.0f); // z + w = -1.5: crosses halfway
    const Drawn image = draw({ front, behind }, { 2 });
    // Halfway in clip space: x_clip = (-0.6875 + 0.9) / 2 = 0.10625, pixel 35.4.
    EXPECT_GT(image.alpha(20, 32), 0.9f);
    EXPECT_GT(image.alpha(34, 32), 0.9f);
    for (int x = 36; x < kSize; ++x)
        EXPECT_EQ(image.alpha(x, 32) + image.alpha(x, 31) + image.alpha(x, 33), 0.0f) << x;
}

TEST(HairSoftwareRaster, HostileSamplesDrawNothingAndNothingElseIsHurt)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<HairRasterSample> samples;
    std::vector<std::uint32_t> ends;
    const auto strand = [&](std::initializer_list<HairRasterSample> points) {
        samples.insert(samples.end(), points);
        ends.push_back(static_cast<std::uint32_t>(samples.size()));
    };
    HairRasterSample bad = at(20.0f, 20.0f, glm::vec3(1.0f), 1.0f);
    bad.clip.x = nan;
    strand({ bad, at(30.0f, 20.0f, glm::vec3(1.0f), 1.0f) });
    HairRasterSample infinite = at(20.0f, 40.0f, glm::vec3(1.0f), 1.0f);
    infinite.clip.y = inf;
    strand({ at(30.0f, 40.0f, glm::vec3(1.0f), 1.0f), infinite });
    strand({ at(1e12f, 5.0f, glm::vec3(1.0f), 1.0f), at(-1e12f, 5.0f, glm::vec3(1.0f), 1.0f) }); // far off both sides
    strand(
        { at(10.0f, 10.0f, glm::vec3(1.0f), 1.0f, 1.0f, -1.0f), at(20.0f, 10.0f, glm::vec3(1.0f), 1.0f, 1.0f, -1.0f) });
    HairRasterSample nanColour = at(40.0f, 50.0f, glm::vec3(1.0f), 1.0f);
    nanColour.colour.y = nan;
    strand({ nanColour, at(50.0f, 50.0f, glm::vec3(1.0f), 1.0f) });
    strand({ at(2.0f, 60.5f, glm::vec3(1.0f), 1.0f, 1e30f),
        at(3.0f, 60.5f, glm::vec3(1.0f), 1.0f, 1e30f) }); // absurd width
    strand({ at(5.0f, 55.5f, glm::vec3(0, 0, 1), 1.0f), at(60.0f, 55.5f, glm::vec3(0, 0, 1), 1.0f) }); // a good one
    ends.push_back(999999); // past the samples: ignored
    const Drawn image = draw(samples, ends);
    for (int x = 4; x < kSize; ++x) { // column 2 is the absurdly wide strand's, all of it
        EXPECT_EQ(image.alpha(x, 20), 0.0f) << x;
        EXPECT_EQ(image.alpha(x, 40), 0.0f) << x;
        EXPECT_EQ(image.alpha(x, 10), 0.0f) << x;
        EXPECT_EQ(image.alpha(x, 50), 0.0f) << x;
    }
    EXPECT_EQ(image.channel(30, 55, 2), 255); // the good strand is there
}

TEST(HairSoftwareRaster, OnlyTheRegionIsDrawnAndReturned)
{
    HairRasterInput input;
    const std::vector<HairRasterSample> samples{ at(0.0f, 20.5f, glm::vec3(1.0f), 1.0f),
        at(64.0f, 20.5f, glm::vec3(1.0f), 1.0f) };
    const std::vector<std::uint32_t> ends{ 2 };
    input.samples = samples;
    input.strandEnds = ends;
    input.width = kSize;
    input.height = kSize;
    input.region = PixelRect{ 16, 10, 48, 30 };
    HairSoftwareRaster raster;
    const std::span<const std::uint8_t> image = raster.draw(input, nullptr);
    ASSERT_EQ(image.size(), 4u * 32 * 20);
    for (int x = 0; x < 32; ++x)
        EXPECT_EQ(image[4 * ((20 - 10) * 32 + x) + 3], 255) << x; // row 20 of the target is row 10 here
}

TEST(HairSoftwareRaster, PixelRectOfAClipRectHoldsThePixelsAGlPassCovers)
{
    const PixelRect whole = pixelRectOfClipRect(glm::vec4(-1.0f, -1.0f, 1.0f, 1.0f), 100, 50);
    EXPECT_EQ(whole.x0, 0);
    EXPECT_EQ(whole.y0, 0);
    EXPECT_EQ(whole.x1, 100);
    EXPECT_EQ(whole.y1, 50);
    // x from 0.1 to 0.5 of 100: pixel centres 10.5 .. 49.5 lie in [10, 50).
    const PixelRect part = pixelRectOfClipRect(glm::vec4(-0.8f, 0.0f, 0.0f, 0.5f), 100, 50);
    EXPECT_EQ(part.x0, 10);
    EXPECT_EQ(part.x1, 50);
    EXPECT_EQ(part.y0, 25);
    EXPECT_EQ(part.y1, 37); // y up to 0.75 of 50 = 37.5: centres 25.5 .. 36.5
}

} // namespace
} // namespace wisp
