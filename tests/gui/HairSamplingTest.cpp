// The level of detail along the strands (widgets/HairSampling.h): how much hair turns, and how many
// samples a segment that asks for on screen.
#include "widgets/HairSampling.h"

#include "widgets/HairStripLayout.h"

#include <glm/trigonometric.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace wisp {
namespace {

// A strand of `points` points, 1 cm segments, each turning `turnRadians` from the last (a circle's
// arc in the xy plane).
void addArc(HairCurves& curves, int points, float turnRadians)
{
    const std::size_t s = curves.addStrand(static_cast<std::uint32_t>(points));
    auto strand = curves.strandForWrite(s);
    glm::vec3 p(0.0f);
    float heading = 0.0f;
    for (int i = 0; i < points; ++i) {
        strand[static_cast<std::size_t>(i)] = p;
        p += 0.01f * glm::vec3(std::cos(heading), std::sin(heading), 0.0f);
        heading += turnRadians;
    }
}

TEST(HairSamplingTest, TheTypicalTurnIsTheNinetiethPercentileOfTheJoints)
{
    HairCurves curves;
    EXPECT_EQ(typicalTurnRadians(curves), 0.0f);
    addArc(curves, 16, 0.0f);
    EXPECT_NEAR(typicalTurnRadians(curves), 0.0f, 1e-3f);
    // Nine straight strands and one curled one: 14 of 140 joints turn, the 90th percentile does not.
    for (int i = 0; i < 8; ++i)
        addArc(curves, 16, 0.0f);
    addArc(curves, 16, 0.5f);
    EXPECT_NEAR(typicalTurnRadians(curves), 0.0f, 1e-3f);
    // Half curled: the 90th percentile is the curl's turn.
    for (int i = 0; i < 10; ++i)
        addArc(curves, 16, 0.3f);
    EXPECT_NEAR(typicalTurnRadians(curves), 0.3f, 1e-3f);
    // A non-finite point or a repeated point is skipped, not a turn of NaN or pi.
    HairCurves broken;
    addArc(broken, 4, 0.2f);
    broken.positions[1] = glm::vec3(std::numeric_limits<float>::quiet_NaN());
    addArc(broken, 4, 0.2f);
    broken.positions[5] = broken.positions[6];
    addArc(broken, 4, 0.2f);
    EXPECT_NEAR(typicalTurnRadians(broken), 0.2f, 1e-3f);
    // Offsets past the points or going backwards: those strands are skipped, nothing read.
    broken.offsets = { 0, 4, 100, 8, 12 };
    EXPECT_NEAR(typicalTurnRadians(broken), 0.2f, 1e-3f);
}

TEST(HairSamplingTest, SamplesASegmentKeepChordsWithinHalfAPixelOfTheCurve)
{
    // kSampleSteps {1, 2, 4}: index 2 is one sample a segment, 1 two, 0 four.
    ASSERT_EQ(HairStripLayout::kSamplesPerSegment, 4u);
    // The default framing: 26 px segments, hanging hair turning ~5 degrees: a chord bows
    // 26 * 0.087 / 8 = 0.28 px, so the points themselves.
    EXPECT_EQ(sampleStepIndex(26.0f, glm::radians(5.0f), 0.5f), 2u);
    // Straight hair at any zoom: one.
    EXPECT_EQ(sampleStepIndex(400.0f, 0.0f, 0.5f), 2u);
    // Turning 0.3 rad: one chord bows 26 * 0.3 / 8 = 0.98 px, two 0.24 px.
    EXPECT_EQ(sampleStepIndex(26.0f, 0.3f, 0.5f), 1u);
    // A close-up of curls, 200 px segments turning 0.5 rad: 12.5 px with one, 3.1 with two,
    // 0.78 with four (the most there is).
    EXPECT_EQ(sampleStepIndex(200.0f, 0.5f, 0.5f), 0u);
    // Exactly at the limit counts as within: 32 px * 0.125 rad / 8 = 0.5 px.
    EXPECT_EQ(sampleStepIndex(32.0f, 0.125f, 0.5f), 2u);
    EXPECT_EQ(sampleStepIndex(std::numeric_limits<float>::quiet_NaN(), 0.2f, 0.5f), 0u);
}

} // namespace
} // namespace wisp
