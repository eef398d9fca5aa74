// The viewport's brush rings, painted growth overlay and hair colours, and that they survive a
// new context.
#include "ViewportTestSupport.h"

using namespace wisp;
using namespace wisp::test;

namespace {

TEST_F(ViewportTest, BrushCursorDrawsARingOnTheHead)
{
    viewport->setFrame(nullptr);
    BrushCursor cursor = foreheadBrush(*viewport, head);
    ASSERT_GT(glm::length(cursor.normal), 0.5f) << "no head under the forehead's pixel";
    const QImage before = grab();
    const glm::vec2 centre = viewport->project(cursor.centre);
    ASSERT_EQ(countPixels(before, isSkin, around(centre, 1)), 9);

    viewport->setBrushCursor(cursor);
    ASSERT_TRUE(viewport->brushCursor().has_value());
    const QImage ring = grab();
    saveScreenshot(ring, "viewport-brush-ring.png");
    int onRing = 0;
    const std::vector<glm::vec3> points = ringPoints(cursor, 24);
    for (const glm::vec3& p : points) {
        const glm::vec2 pixel = viewport->project(p);
        const int white = countPixels(ring, isNearWhite, around(pixel, 1));
        onRing += white >= 2 ? 1 : 0;
        EXPECT_EQ(countPixels(before, isNearWhite, around(pixel, 1)), 0);
    }
    EXPECT_GE(onRing, 23) << "of " << points.size() << " points on the ring";
    // A ring, not a disc: the middle is still skin, and so is a point halfway out.
    EXPECT_EQ(countPixels(ring, isSkin, around(centre, 1)), 9);
    const glm::vec2 halfway = 0.5f * (centre + viewport->project(points[3]));
    EXPECT_EQ(countPixels(ring, isSkin, around(halfway, 1)), 9);

    // Mirrored: a second ring on the other side, dimmer (blended: brighter than what is under it,
    // short of white; fainter still where the head hides it).
    cursor.mirrored = true;
    cursor.mirrorCentre = cursor.centre * glm::vec3(-1.0f, 1.0f, 1.0f);
    cursor.mirrorNormal = cursor.normal * glm::vec3(-1.0f, 1.0f, 1.0f);
    viewport->setBrushCursor(cursor);
    const QImage mirrored = grab();
    BrushCursor mirror = cursor;
    mirror.centre = cursor.mirrorCentre;
    mirror.normal = cursor.mirrorNormal;
    int brighter = 0;
    for (const glm::vec3& p : ringPoints(mirror, 24)) {
        const QRect area = around(viewport->project(p), 1);
        const auto brightest = [&](const QImage& image) {
            int most = 0;
            for (int y = area.top(); y <= area.bottom(); ++y)
                for (int x = area.left(); x <= area.right(); ++x)
                    most = std::max(most, image.pixelColor(x, y).blue());
            return most;
        };
        brighter += brightest(mirrored) >= brightest(before) + 10 ? 1 : 0;
        EXPECT_EQ(countPixels(mirrored, isNearWhite, area), 0);
    }
    EXPECT_GE(brighter, 22);

    // Erasing tints it red.
    cursor.erase = true;
    viewport->setBrushCursor(cursor);
    const QImage erase = grab();
    int red = 0;
    for (const glm::vec3& p : points)
        red += countPixels(erase, isEraseRed, around(viewport->project(p), 1)) >= 2 ? 1 : 0;
    EXPECT_GE(red, 23);

    // Gone again.
    viewport->setBrushCursor(std::nullopt);
    EXPECT_EQ(differingPixels(grab(), before), 0);
}

TEST_F(ViewportTest, GrowthOverlayTintsTheWeightedHalfOfTheHead)
{
    viewport->setFrame(nullptr); // nothing in front of the skin
    const TriangleMesh& mesh = defaultHead().mesh;
    const float middleY = head.center().y;
    std::vector<float> weights(mesh.positions.size());
    for (std::size_t i = 0; i < weights.size(); ++i)
        weights[i] = mesh.positions[i].y > middleY ? 1.0f : 0.0f;
    // Well away from the boundary, where the weight is blended across triangles.
    const auto upper
        = visibleFacingVertex(*viewport, [&](std::size_t i) { return mesh.positions[i].y > middleY + 0.03f; });
    const auto lower
        = visibleFacingVertex(*viewport, [&](std::size_t i) { return mesh.positions[i].y < middleY - 0.03f; });
    ASSERT_TRUE(upper && lower);
    const QRect upperArea = around(viewport->project(mesh.positions[*upper]), 1);
    const QRect lowerArea = around(viewport->project(mesh.positions[*lower]), 1);
    const QImage plain = grab();
    ASSERT_EQ(countPixels(plain, isSkin, upperArea), 9);
    ASSERT_EQ(countPixels(plain, isSkin, lowerArea), 9);

    // The tint is a painting aid: off until asked for (the editor asks while painting).
    EXPECT_FALSE(viewport->showGrowthOverlay());
    viewport->setGrowthOverlay(weights);
    EXPECT_EQ(differingPixels(grab(), plain), 0);
    viewport->setShowGrowthOverlay(true);
    const QImage tinted = grab();
    saveScreenshot(tinted, "viewport-growth-overlay.png");
    EXPECT_EQ(countPixels(tinted, isGrowthTint, upperArea), 9);
    EXPECT_EQ(differingPixels(plain.copy(lowerArea), tinted.copy(lowerArea)), 0);

    viewport->setShowGrowthOverlay(false);
    EXPECT_FALSE(viewport->showGrowthOverlay());
    EXPECT_EQ(differingPixels(grab(), plain), 0);
    viewport->setShowGrowthOverlay(true);
    EXPECT_EQ(countPixels(grab(), isGrowthTint, upperArea), 9);

    // Weights for some other mesh are not shown.
    viewport->setGrowthOverlay(std::vector<float>(10, 1.0f));
    EXPECT_EQ(differingPixels(grab(), plain), 0);

    // A brush stroke sends new weights many times a second: time it on this head (printed only).
    QElapsedTimer timer;
    timer.start();
    constexpr int kUpdates = 20;
    for (int k = 0; k < kUpdates; ++k) {
        weights[static_cast<std::size_t>(k)] = 0.5f;
        viewport->setGrowthOverlay(weights);
        viewport->repaint();
    }
    std::printf("[ viewport ] %zu head vertices: a weight update and repaint takes %.1f ms\n", weights.size(),
        static_cast<double>(timer.elapsed()) / kUpdates);
    EXPECT_EQ(countPixels(grab(), isGrowthTint, upperArea), 9);
}

TEST_F(ViewportTest, GrowthOverlayAndBrushOnTheDefaultScalp)
{
    viewport->setFrame(nullptr);
    const TriangleMesh& mesh = defaultHead().mesh;
    const std::vector<float>& weights = defaultHead().growthWeights;
    ASSERT_EQ(weights.size(), mesh.positions.size());
    BrushCursor cursor = foreheadBrush(*viewport, head);
    cursor.mirrored = true;
    cursor.mirrorCentre = cursor.centre * glm::vec3(-1.0f, 1.0f, 1.0f);
    cursor.mirrorNormal = cursor.normal * glm::vec3(-1.0f, 1.0f, 1.0f);
    // On the crown, well inside the painted area, off the brush's rings.
    const auto scalp = visibleFacingVertex(*viewport, [&](std::size_t i) {
        return weights[i] > 0.99f && mesh.positions[i].y > head.max.y - 0.05f
            && clearOfTheRings(cursor, mesh.positions[i]);
    });
    ASSERT_TRUE(scalp);
    viewport->setGrowthOverlay(weights);
    viewport->setShowGrowthOverlay(true);
    viewport->setBrushCursor(cursor);
    const QImage image = grab();
    saveScreenshot(image, "viewport-scalp-overlay-and-brush.png");
    EXPECT_EQ(countPixels(image, isGrowthTint, around(viewport->project(mesh.positions[*scalp]), 1)), 9);
    // The face grows no hair: the middle of the view is plain skin.
    EXPECT_EQ(countPixels(image, isSkin, around(viewport->project(head.center()), 2)), 25);
}

TEST_F(ViewportTest, StrandsTakeTheirLooksColours)
{
    // Two locks side by side, one red and one blue, and a third whose look does not exist (the
    // viewport's own green).
    auto frame = std::make_shared<Frame>();
    const glm::vec3 redTop = lockTop(head);
    const glm::vec3 blueTop = lockTop(head) + glm::vec3(0.0f, 0.0f, -0.06f);
    const glm::vec3 greenTop = lockTop(head) + glm::vec3(0.0f, 0.0f, 0.06f);
    addLock(frame->strands, redTop, 120, 16, kLockLength);
    addLock(frame->strands, blueTop, 120, 16, kLockLength);
    addLock(frame->strands, greenTop, 120, 16, kLockLength);
    StrandLook red;
    red.rootColour = red.tipColour = glm::vec3(1.0f, 0.0f, 0.0f);
    StrandLook blue;
    blue.rootColour = blue.tipColour = glm::vec3(0.0f, 0.0f, 1.0f);
    frame->looks.push_back(red);
    frame->looks.push_back(blue);
    frame->lookOfStrand.assign(120, 0);
    frame->lookOfStrand.insert(frame->lookOfStrand.end(), 120, 1);
    frame->lookOfStrand.insert(frame->lookOfStrand.end(), 120, 7);
    viewport->setFrame(frame);
    const QImage image = grab();
    saveScreenshot(image, "viewport-strand-looks.png");
    const auto middleOf = [&](const glm::vec3& top, float along) {
        return around(viewport->project(top - glm::vec3(0.0f, along * kLockLength, 0.0f)), 2);
    };
    for (float along : { 0.25f, 0.5f, 0.75f }) {
        EXPECT_GE(countPixels(image, isRed, middleOf(redTop, along)), 15) << along;
        EXPECT_EQ(countPixels(image, isBlue, middleOf(redTop, along)), 0) << along;
        EXPECT_GE(countPixels(image, isBlue, middleOf(blueTop, along)), 15) << along;
        EXPECT_EQ(countPixels(image, isRed, middleOf(blueTop, along)), 0) << along;
        EXPECT_GE(countPixels(image, isGreenHair, middleOf(greenTop, along)), 15) << along;
    }

    // New looks on the same strands (a region's colour edited): the colours follow.
    auto swapped = std::make_shared<Frame>(*frame);
    std::swap(swapped->looks[0], swapped->looks[1]);
    viewport->setFrame(swapped);
    const QImage after = grab();
    EXPECT_GE(countPixels(after, isBlue, middleOf(redTop, 0.5f)), 15);
    EXPECT_GE(countPixels(after, isRed, middleOf(blueTop, 0.5f)), 15);

    // Without looks, every strand takes the viewport's colours.
    auto plain = std::make_shared<Frame>(*frame);
    plain->looks.clear();
    plain->lookOfStrand.clear();
    viewport->setFrame(plain);
    const QImage green = grab();
    EXPECT_GE(countPixels(green, isGreenHair, middleOf(redTop, 0.5f)), 15);
    EXPECT_GE(countPixels(green, isGreenHair, middleOf(blueTop, 0.5f)), 15);
}

TEST_F(ViewportTest, OverlayBrushAndLooksSurviveANewContext)
{
    const TriangleMesh& mesh = defaultHead().mesh;
    const std::vector<float>& weights = defaultHead().growthWeights;
    BrushCursor cursor = foreheadBrush(*viewport, head);
    const auto scalp = visibleFacingVertex(*viewport, [&](std::size_t i) {
        return weights[i] > 0.99f && mesh.positions[i].y > head.max.y - 0.05f
            && clearOfTheRings(cursor, mesh.positions[i]);
    });
    ASSERT_TRUE(scalp);
    viewport->setGrowthOverlay(weights);
    viewport->setShowGrowthOverlay(true);
    viewport->setBrushCursor(cursor);
    auto frame = lockFrame(head);
    StrandLook red;
    red.rootColour = red.tipColour = glm::vec3(1.0f, 0.0f, 0.0f);
    frame->looks.push_back(red);
    frame->lookOfStrand.assign(frame->strands.strandCount(), 0);
    viewport->setFrame(frame);
    grab();

    // Moving the widget into another window gives it a new GL context: all of it is sent again.
    const ViewportInNewWindow newWindow(*viewport);
    ASSERT_TRUE(newWindow.exposed());
    const QImage moved = grab();
    EXPECT_EQ(countPixels(moved, isGrowthTint, around(viewport->project(mesh.positions[*scalp]), 1)), 9);
    int onRing = 0;
    for (const glm::vec3& p : ringPoints(cursor, 24))
        onRing += countPixels(moved, isNearWhite, around(viewport->project(p), 1)) >= 2 ? 1 : 0;
    EXPECT_GE(onRing, 23);
    const glm::vec2 lock = viewport->project(lockTop(head) - glm::vec3(0.0f, 0.5f * kLockLength, 0.0f));
    EXPECT_GE(countPixels(moved, isRed, around(lock, 2)), 15);
}

} // namespace
