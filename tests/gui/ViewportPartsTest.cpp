// The viewport's pure parts, without a widget: the orbit camera, the strand layout and level of
// detail, the HUD line and the guide geometry.
#include "ViewportTestSupport.h"

using namespace wisp;
using namespace wisp::test;

namespace {

TEST(OrbitCameraTest, FramesBoundsInTheMiddleAndKeepsDirection)
{
    OrbitCamera camera;
    const Aabb box{ { -0.1f, -0.2f, -0.1f }, { 0.1f, 0.1f, 0.1f } };
    camera.orbit(40.0f, -25.0f);
    const glm::vec3 direction = camera.forward();
    camera.frame(box, 1.5f);
    EXPECT_NEAR(glm::length(camera.pivot() - box.center()), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(camera.forward(), direction), 1.0f, 1e-6f);
    const glm::vec2 centre = camera.project(box.center(), { 600.0f, 400.0f });
    EXPECT_NEAR(centre.x, 300.0f, 0.01f);
    EXPECT_NEAR(centre.y, 200.0f, 0.01f);
    // Every corner of the box is on screen.
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner{ i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y,
            i & 4 ? box.max.z : box.min.z };
        const glm::vec2 p = camera.project(corner, { 600.0f, 400.0f });
        EXPECT_GT(p.x, 0.0f);
        EXPECT_LT(p.x, 600.0f);
        EXPECT_GT(p.y, 0.0f);
        EXPECT_LT(p.y, 400.0f);
    }
}

TEST(OrbitCameraTest, YIsUpAndPanFollowsTheCursor)
{
    OrbitCamera camera;
    camera.reset({ { -0.1f, -0.1f, -0.1f }, { 0.1f, 0.1f, 0.1f } }, 1.0f);
    EXPECT_GT(camera.up().y, 0.9f);
    EXPECT_GT(camera.eye().y, camera.pivot().y); // the start-up view looks slightly down
    const glm::vec2 size{ 500.0f, 500.0f };
    const glm::vec3 point = camera.pivot();
    const glm::vec2 before = camera.project(point, size);
    camera.pan(30.0f, -20.0f, size.y);
    const glm::vec2 after = camera.project(point, size);
    EXPECT_NEAR(after.x - before.x, 30.0f, 0.05f);
    EXPECT_NEAR(after.y - before.y, -20.0f, 0.05f);
    const float distance = camera.distance();
    camera.zoom(1.0f);
    EXPECT_NEAR(camera.distance(), distance * OrbitCamera::kZoomPerStep, 1e-6f);
    camera.orbit(0.0f, 1e6f); // pitch stops short of the pole
    EXPECT_LE(camera.pitch(), OrbitCamera::kMaxPitchRadians);
    camera.zoom(std::numeric_limits<float>::quiet_NaN());
    EXPECT_TRUE(std::isfinite(camera.distance()));
}

TEST(HairStripLayoutTest, EveryLevelOfDetailKeepsRootsAndTipsAndSkipsPointlessStrands)
{
    // Strands of 16, 2, 1, 0 and 3 points.
    const std::vector<std::uint32_t> offsets{ 0, 16, 18, 19, 19, 22 };
    const HairStripLayout layout = buildHairStripLayout(offsets);
    EXPECT_EQ(layout.drawnStrands, 3u);
    EXPECT_TRUE(layout.matches(offsets));
    const std::uint32_t samplesPer = HairStripLayout::kSamplesPerSegment;
    // Two vertices per sample: 15, 1 and 2 segments of kSamplesPerSegment samples, plus the tips.
    EXPECT_EQ(layout.vertices.size(), 2u * ((15 + 1 + 2) * samplesPer + 3));
    for (std::size_t step = 0; step < HairStripLayout::kSampleSteps.size(); ++step) {
        const auto& lines = layout.lines[step];
        const auto& ribbons = layout.ribbons[step];
        ASSERT_EQ(lines.prefix.size(), 4u);
        EXPECT_EQ(lines.prefix.back(), lines.indices.size());
        EXPECT_EQ(ribbons.prefix.back(), ribbons.indices.size());
        // Each strip starts at a root sample and ends at a tip sample, then a restart.
        std::size_t begin = 0;
        for (std::size_t k = 1; k < lines.prefix.size(); ++k) {
            const std::size_t end = lines.prefix[k];
            ASSERT_GE(end - begin, 3u);
            EXPECT_EQ(lines.indices[end - 1], HairStripLayout::kRestart);
            const glm::uvec2 root = layout.vertices[lines.indices[begin]];
            const glm::uvec2 tip = layout.vertices[lines.indices[end - 2]];
            EXPECT_EQ(root.y & 0xFFFu, 0u);
            EXPECT_EQ((root.y >> HairStripLayout::kSampleShift) & 0x1Fu, 0u);
            const std::uint32_t segments = (tip.y >> HairStripLayout::kSegmentBits) & 0xFFFu;
            EXPECT_EQ(tip.y & 0xFFFu, segments - 1);
            EXPECT_EQ((tip.y >> HairStripLayout::kSampleShift) & 0x1Fu, samplesPer);
            EXPECT_EQ(end - begin - 1, segments * samplesPer / HairStripLayout::kSampleSteps[step] + 1);
            begin = end;
        }
        // Ribbons: both edges of every sample line takes.
        EXPECT_EQ(ribbons.indices.size(), 2 * (lines.indices.size() - 3) + 3);
    }
    // Decreasing offsets are refused, not read.
    EXPECT_EQ(buildHairStripLayout(std::vector<std::uint32_t>{ 0, 10, 5 }).drawnStrands, 1u);
}

TEST(HairStripLayoutTest, PrefixesAreEvenSamplesOfTheStrands)
{
    // 1000 strands in groom order; the first tenth of the drawing order should come from all over
    // that order, not from its start.
    std::vector<std::uint32_t> offsets{ 0 };
    for (int s = 0; s < 1000; ++s)
        offsets.push_back(offsets.back() + 4);
    const HairStripLayout layout = buildHairStripLayout(offsets);
    int quarters[4] = { 0, 0, 0, 0 };
    const auto& lines = layout.lines[0];
    for (std::size_t k = 0; k < 100; ++k) {
        const std::uint32_t point = layout.vertices[lines.indices[lines.prefix[k]]].x;
        ++quarters[std::min(3u, point / 4 / 250)];
    }
    for (int q : quarters)
        EXPECT_GT(q, 12) << q;
}

TEST(HairDetailTest, PreviewsWhenOverBudgetAndRecovers)
{
    HairDetail detail;
    const std::size_t strands = 4600;
    EXPECT_FALSE(detail.previewing());
    EXPECT_EQ(detail.fraction(strands), 1.0f);
    detail.paintTook(HairDetail::kBudgetMilliseconds * 0.5, false, 1.0f, strands);
    EXPECT_FALSE(detail.previewing());
    // Too slow: preview, coarse curves with every strand first, then fewer strands.
    detail.paintTook(HairDetail::kBudgetMilliseconds * 4.0, false, 1.0f, strands);
    EXPECT_TRUE(detail.previewing());
    EXPECT_EQ(detail.fraction(strands), 1.0f);
    detail.paintTook(HairDetail::kBudgetMilliseconds * 1.6, true, 1.0f, strands);
    const float cut = detail.fraction(strands);
    EXPECT_LT(cut, 0.8f);
    EXPECT_GE(cut, static_cast<float>(HairDetail::kMinimumStrands) / strands);
    // Never below the floor, however slow.
    for (int i = 0; i < 20; ++i)
        detail.paintTook(1000.0, true, detail.fraction(strands), strands);
    EXPECT_NEAR(detail.fraction(strands) * strands,
        std::max(HairDetail::kMinimumFraction * strands, static_cast<float>(HairDetail::kMinimumStrands)), 1.0f);
    EXPECT_NEAR(detail.fraction(strands), 1.0f / 3.0f, 1e-6f); // ribbons at most three times as wide
    // Fast again: the fraction grows back, then preview ends.
    for (int i = 0; i < 30; ++i)
        detail.paintTook(HairDetail::kBudgetMilliseconds * 0.3, true, detail.fraction(strands), strands);
    EXPECT_FALSE(detail.previewing());
    // Small grooms are always drawn whole.
    detail.paintTook(1000.0, false, 1.0f, 300);
    EXPECT_FALSE(detail.previewing());
    EXPECT_EQ(detail.fraction(300), 1.0f);
}

TEST(ViewportOverlayTest, HudLine)
{
    Frame frame;
    addLock(frame.strands, glm::vec3(0.0f), 3, 4, 0.1f);
    frame.simulatedParticles = 7632;
    frame.stepMilliseconds = 0.1234;
    EXPECT_EQ(composeHudText(&frame, 59.7), QStringLiteral("fps 60 · sim 0.12 ms/step · 3 strands · 7632 particles"));
    frame.timeScale = 0.5;
    frame.fallingBehind = true;
    EXPECT_EQ(composeHudText(&frame, 30.0),
        QStringLiteral("fps 30 · sim 0.12 ms/step · 3 strands · 7632 particles · slow motion x0.5 · falling behind"));
    EXPECT_EQ(composeHudText(nullptr, std::numeric_limits<double>::quiet_NaN()), QStringLiteral("fps 0 · no hair"));
    frame.timeScale = 1.0;
    frame.fallingBehind = false;
    EXPECT_TRUE(composeHudText(&frame, 30.0, 0.4, true).endsWith(QStringLiteral("particles · preview 40%")));
    EXPECT_TRUE(composeHudText(&frame, 30.0, 1.0, true).endsWith(QStringLiteral("particles · preview")));
    // Paused: no stale frame rate or solver time.
    EXPECT_EQ(composeHudText(&frame, 30.0, 1.0, false, true), QStringLiteral("paused · 3 strands · 7632 particles"));
    EXPECT_EQ(composeHudText(nullptr, 30.0, 1.0, false, true), QStringLiteral("paused · no hair"));
}

TEST(GuideGeometryTest, WindArrowPointsAtTheHeadFromUpwindAndScalesWithSpeed)
{
    const Aabb head{ { -0.09f, -0.23f, -0.11f }, { 0.09f, 0.14f, 0.12f } };
    EXPECT_FALSE(buildWindArrow(head, glm::vec3(0.0f)).visible);
    EXPECT_FALSE(buildWindArrow(head, glm::vec3(std::numeric_limits<float>::quiet_NaN())).visible);
    const WindArrow slow = buildWindArrow(head, { 2.0f, 0.0f, 0.0f });
    const WindArrow fast = buildWindArrow(head, { 10.0f, 0.0f, 0.0f });
    ASSERT_TRUE(slow.visible);
    EXPECT_LT(slow.tip.x, head.min.x); // blowing toward +X: it comes from -X
    EXPECT_GT(fast.tip.x - fast.tail.x, slow.tip.x - slow.tail.x);
    EXPECT_FALSE(fast.triangles.empty());
    const GroundGrid grid = buildGroundGrid(head);
    EXPECT_FLOAT_EQ(grid.centre.y, head.min.y);
    EXPECT_FALSE(grid.lines.empty());
}

} // namespace
