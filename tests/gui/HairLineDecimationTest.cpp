// Lines with the straight runs' points left out (widgets/HairLineDecimation.h): which points go,
// what is kept whatever the tolerance, and that no chord strays further than asked.
#include "widgets/HairLineDecimation.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

namespace wisp {
namespace {

// The points (as indices into curves.positions) a line list draws for drawn strand d, in order.
std::vector<std::uint32_t> drawnPoints(
    const HairStripLayout& layout, const HairStripLayout::IndexList& list, std::size_t d)
{
    std::vector<std::uint32_t> points;
    const std::uint32_t s = layout.strandOrder[d];
    for (std::uint32_t n = list.prefix[d]; n + 1 < list.prefix[d + 1]; ++n) {
        const std::uint32_t sample = (list.indices[n] - layout.firstVertex[d]) / 2;
        EXPECT_EQ(sample % HairStripLayout::kSamplesPerSegment, 0u); // the points themselves
        points.push_back(layout.offsets[s] + sample / HairStripLayout::kSamplesPerSegment);
    }
    EXPECT_EQ(list.indices[list.prefix[d + 1] - 1], HairStripLayout::kRestart);
    return points;
}

TEST(HairLineDecimation, StraightRunsLoseEveryOtherPointAndBendsKeepTheirs)
{
    HairCurves curves;
    // A straight strand of 16 points, 1 cm apart.
    const std::size_t straight = curves.addStrand(16);
    for (int i = 0; i < 16; ++i)
        curves.strandForWrite(straight)[static_cast<std::size_t>(i)] = glm::vec3(0.0f, -0.01f * i, 0.0f);
    // A strand straight but for a sharp kink at point 5 (a right angle) and a gentle one at 10.
    const std::size_t kinked = curves.addStrand(16);
    glm::vec3 p(0.1f, 0.0f, 0.0f);
    for (int i = 0; i < 16; ++i) {
        curves.strandForWrite(kinked)[static_cast<std::size_t>(i)] = p;
        p += i < 5   ? glm::vec3(0.0f, -0.01f, 0.0f)
            : i < 10 ? glm::vec3(0.01f, 0.0f, 0.0f)
                     : glm::vec3(0.01f, -0.0005f, 0.0f);
    }
    // Two points only: nothing to leave out.
    const std::size_t shortest = curves.addStrand(2);
    curves.strandForWrite(shortest)[0] = glm::vec3(0.2f, 0.0f, 0.0f);
    curves.strandForWrite(shortest)[1] = glm::vec3(0.2f, -0.01f, 0.0f);

    const HairStripLayout layout = buildHairStripLayout(curves.offsets);
    ASSERT_EQ(layout.drawnStrands, 3u);
    const std::vector<float> deviations = chordDeviations(curves);
    ASSERT_EQ(deviations.size(), curves.pointCount());
    EXPECT_TRUE(std::isinf(deviations[0]) && std::isinf(deviations[15])); // the ends: never left out
    EXPECT_NEAR(deviations[16 + 5], 0.01f / std::sqrt(2.0f), 1e-6f); // the right angle

    // Tolerance 0.1 mm: the straight strand loses every other point; the kinked one keeps point 5
    // (7 mm off its chord) and the points of its gentle bend at 10 (0.25 mm off).
    const HairStripLayout::IndexList list = decimatedLines(layout, deviations, 1e-4f);
    ASSERT_EQ(list.prefix.size(), 4u);
    for (std::size_t d = 0; d < 3; ++d) {
        const std::vector<std::uint32_t> points = drawnPoints(layout, list, d);
        const std::uint32_t s = layout.strandOrder[d];
        const std::uint32_t begin = curves.offsets[s], end = curves.offsets[s + 1];
        ASSERT_GE(points.size(), 2u);
        EXPECT_EQ(points.front(), begin); // the root and the tip, always
        EXPECT_EQ(points.back(), end - 1);
        for (std::size_t k = 1; k < points.size(); ++k)
            EXPECT_LE(points[k] - points[k - 1], 2u); // a chord spans at most two segments
        const std::set<std::uint32_t> kept(points.begin(), points.end());
        if (s == straight) {
            EXPECT_EQ(points.size(), 9u); // 0, 2, 4, ..., 14, 15
        }
        if (s == kinked) {
            EXPECT_TRUE(kept.count(begin + 5)); // the right angle
            EXPECT_TRUE(kept.count(begin + 10)); // the gentle bend: 0.25 mm off its chord
            EXPECT_LT(points.size(), 16u);
        }
        if (s == shortest) {
            EXPECT_EQ(points.size(), 2u);
        }
        // No point left out lies further than the tolerance from the chord drawn past it.
        for (std::size_t k = 1; k < points.size(); ++k) {
            if (points[k] - points[k - 1] == 2) {
                EXPECT_LE(deviations[points[k - 1] + 1], 1e-4f);
            }
        }
    }
    // A tolerance of zero (or none) leaves the one-sample lines as they were.
    for (const float tolerance : { -1.0f, std::numeric_limits<float>::quiet_NaN() }) {
        const HairStripLayout::IndexList all = decimatedLines(layout, deviations, tolerance);
        EXPECT_EQ(all.indices, layout.lines[kOneSampleStep].indices);
        EXPECT_EQ(all.prefix, layout.lines[kOneSampleStep].prefix);
    }
    // Deviations of other strands (another point count): nothing is left out.
    const std::vector<float> other(5, 0.0f);
    EXPECT_EQ(decimatedLines(layout, other, 1.0f).indices, layout.lines[kOneSampleStep].indices);
}

TEST(HairLineDecimation, NonFinitePointsAreNeverLeftOut)
{
    HairCurves curves;
    const std::size_t s = curves.addStrand(5);
    for (int i = 0; i < 5; ++i)
        curves.strandForWrite(s)[static_cast<std::size_t>(i)] = glm::vec3(0.0f, -0.01f * i, 0.0f);
    curves.strandForWrite(s)[2].x = std::numeric_limits<float>::quiet_NaN();
    const std::vector<float> deviations = chordDeviations(curves);
    for (int i = 1; i < 4; ++i)
        EXPECT_TRUE(std::isinf(deviations[static_cast<std::size_t>(i)])) << i; // next to or at the NaN
}

} // namespace
} // namespace wisp
