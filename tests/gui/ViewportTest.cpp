// The viewport widget: what it draws where, camera input, the HUD, bad frames and lost contexts,
// the grid and the wind arrow, strand width, picking rays.
#include "ViewportTestSupport.h"

using namespace wisp;
using namespace wisp::test;

namespace {

TEST_F(ViewportTest, DrawsSkinHairAndBackgroundWhereTheyProject)
{
    viewport->setFrame(lockFrame(head));
    const QImage image = grab();
    ASSERT_EQ(image.size(), QSize(640, 480));

    const glm::vec2 headCentre = viewport->project(head.center());
    EXPECT_EQ(countPixels(image, isSkin, around(headCentre, 2)), 25)
        << "head centre at " << headCentre.x << ", " << headCentre.y;

    // Down the middle of the lock: hair-coloured, with at least most of a small window covered.
    for (float along : { 0.25f, 0.5f, 0.75f }) {
        const glm::vec2 p = viewport->project(lockTop(head) - glm::vec3(0.0f, along * kLockLength, 0.0f));
        EXPECT_GE(countPixels(image, isGreenHair, around(p, 2)), 15)
            << "lock at " << along << ": " << p.x << ", " << p.y;
    }
    // Top-right corner (the HUD is top-left, the gizmo bottom-left): background.
    EXPECT_TRUE(near(image.pixelColor(637, 2), Viewport::backgroundColour(2.5 / 480.0), 6))
        << image.pixelColor(637, 2).name().toStdString();
    EXPECT_EQ(countPixels(image, isGreenHair, QRect(560, 0, 80, 60)), 0);
    EXPECT_GE(viewport->samples(), 0);
}

TEST_F(ViewportTest, StartsOnAThreeQuarterViewOfTheHeadInTheMiddle)
{
    const glm::vec2 centre = viewport->project(head.center());
    EXPECT_NEAR(centre.x, 320.0f, 1.0f);
    EXPECT_NEAR(centre.y, 240.0f, 1.0f);
    // Neither front nor profile: the camera is off both the Z axis and the X axis, and above.
    const glm::vec3 eye = viewport->camera().eye() - head.center();
    EXPECT_GT(eye.x, 0.2f * glm::length(eye));
    EXPECT_GT(eye.z, 0.5f * glm::length(eye));
    EXPECT_GT(eye.y, 0.0f);
    const QImage image = grab();
    // The head fills a good part of the view without touching its edges.
    const int skin = skinPixels(image);
    EXPECT_GT(skin, 640 * 480 / 10);
    EXPECT_EQ(countPixels(image, isSkin, QRect(0, 0, 640, 4)), 0);
    EXPECT_EQ(countPixels(image, isSkin, QRect(0, 476, 640, 4)), 0);
}

TEST_F(ViewportTest, WheelZoomsTowardThePivot)
{
    const int before = skinPixels(grab());
    const float distance = viewport->camera().distance();
    const glm::vec3 pivot = viewport->camera().pivot();
    wheel(viewport.get(), 240);
    EXPECT_LT(viewport->camera().distance(), distance);
    EXPECT_EQ(viewport->camera().pivot(), pivot);
    const int after = skinPixels(grab());
    EXPECT_GT(after, before * 1.3) << before << " -> " << after;
    wheel(viewport.get(), -480);
    EXPECT_GT(viewport->camera().distance(), distance);
}

TEST_F(ViewportTest, MiddleDragOrbitsShiftMiddleDragPansAltLeftDragOrbits)
{
    const QImage start = grab();
    const float yaw = viewport->camera().yaw();
    drag(viewport.get(), Qt::MiddleButton, Qt::NoModifier, { 300, 240 }, { 380, 240 });
    EXPECT_NEAR(viewport->camera().yaw(), yaw - 80.0f * OrbitCamera::kOrbitRadiansPerPixel, 1e-4f);
    const QImage orbited = grab();
    EXPECT_GT(differingPixels(start, orbited), 5000);
    // The pivot stays on the head: it is still in the middle after orbiting.
    const glm::vec2 centre = viewport->project(head.center());
    EXPECT_NEAR(centre.x, 320.0f, 1.0f);

    // Pan: the head follows the cursor.
    drag(viewport.get(), Qt::MiddleButton, Qt::ShiftModifier, { 300, 240 }, { 340, 210 });
    const glm::vec2 panned = viewport->project(head.center());
    EXPECT_NEAR(panned.x - centre.x, 40.0f, 1.0f);
    EXPECT_NEAR(panned.y - centre.y, -30.0f, 1.0f);
    EXPECT_EQ(countPixels(grab(), isSkin, around(panned, 2)), 25);

    const float pitch = viewport->camera().pitch();
    drag(viewport.get(), Qt::LeftButton, Qt::AltModifier, { 300, 240 }, { 300, 280 });
    EXPECT_NEAR(viewport->camera().pitch(), pitch + 40.0f * OrbitCamera::kOrbitRadiansPerPixel, 1e-4f);

    // A plain left drag belongs to the editor's tools: the camera stays.
    const glm::vec3 eye = viewport->camera().eye();
    drag(viewport.get(), Qt::LeftButton, Qt::NoModifier, { 300, 240 }, { 400, 300 });
    EXPECT_EQ(viewport->camera().eye(), eye);
}

TEST_F(ViewportTest, FKeyFramesTheHead)
{
    drag(viewport.get(), Qt::MiddleButton, Qt::ShiftModifier, { 300, 240 }, { 500, 400 });
    wheel(viewport.get(), -360);
    drag(viewport.get(), Qt::MiddleButton, Qt::NoModifier, { 300, 240 }, { 200, 200 });
    EXPECT_EQ(countPixels(grab(), isSkin, QRect(318, 238, 5, 5)), 0); // the head has left the middle

    viewport->setFocus();
    QTest::keyClick(viewport.get(), Qt::Key_F);
    const glm::vec2 centre = viewport->project(head.center());
    EXPECT_NEAR(centre.x, 320.0f, 1.0f);
    EXPECT_NEAR(centre.y, 240.0f, 1.0f);
    const QImage image = grab();
    EXPECT_EQ(countPixels(image, isSkin, QRect(318, 238, 5, 5)), 25);
    EXPECT_GT(skinPixels(image), 640 * 480 / 10);

    // frameHead() (the menu's action) does the same.
    wheel(viewport.get(), 600);
    viewport->frameHead();
    EXPECT_NEAR(viewport->project(head.center()).x, 320.0f, 1.0f);
}

TEST_F(ViewportTest, HudShowsTheFramesNumbers)
{
    auto frame = lockFrame(head, 77);
    frame->simulatedParticles = 1234;
    viewport->setFrame(frame);
    grab();
    EXPECT_TRUE(viewport->hudText().contains(QStringLiteral("77 strands"))) << viewport->hudText().toStdString();
    EXPECT_TRUE(viewport->hudText().contains(QStringLiteral("1234 particles")));
    EXPECT_TRUE(viewport->hudText().contains(QStringLiteral("sim 0.12 ms/step")));
    EXPECT_FALSE(viewport->hudText().contains(QStringLiteral("slow motion")));

    auto slow = std::make_shared<Frame>(*frame);
    slow->timeScale = 0.25;
    slow->fallingBehind = true;
    viewport->setFrame(slow);
    EXPECT_TRUE(viewport->hudText().contains(QStringLiteral("slow motion x0.25")));
    EXPECT_TRUE(viewport->hudText().contains(QStringLiteral("falling behind")));
    // The HUD is painted over the GL content, top-left: light text there, none without it.
    const QImage image = grab();
    EXPECT_GT(countPixels(
                  image, [](QColor c) { return c.lightness() > 180; }, QRect(0, 0, 300, 30)),
        20);
}

TEST_F(ViewportTest, FrameRateIsMeasuredAndReported)
{
    double reported = -1.0;
    QObject::connect(viewport.get(), &Viewport::fpsChanged, [&](double fps) { reported = fps; });
    viewport->setFrame(lockFrame(head));
    for (int i = 0; i < 12; ++i) {
        viewport->repaint();
        QTest::qWait(20); // at most ~50 paints a second
    }
    EXPECT_GT(viewport->framesPerSecond(), 1.0);
    EXPECT_LT(viewport->framesPerSecond(), 100.0);
    EXPECT_GE(reported, 0.0);
    EXPECT_TRUE(viewport->hudText().startsWith(QStringLiteral("fps ")));
}

TEST_F(ViewportTest, BadFramesDrawWhatTheyCanAndNeverCrash)
{
    viewport->setFrame(nullptr);
    grab();
    EXPECT_TRUE(viewport->hudText().contains(QStringLiteral("no hair")));
    viewport->setFrame(std::make_shared<Frame>());
    grab();
    EXPECT_TRUE(viewport->hudText().contains(QStringLiteral("0 strands")));

    // A good lock, then strands of 0, 1 and 2 points, then a sheet of strands across the head's
    // centre with one NaN (or infinite) point each, which must not be drawn at all.
    auto frame = lockFrame(head);
    frame->strands.addStrand(0);
    const std::size_t one = frame->strands.addStrand(1);
    frame->strands.strandForWrite(one)[0] = head.center();
    const std::size_t two = frame->strands.addStrand(2);
    frame->strands.strandForWrite(two)[0] = lockTop(head) + glm::vec3(0.0f, 0.0f, 0.03f);
    frame->strands.strandForWrite(two)[1] = lockTop(head) + glm::vec3(0.0f, -0.1f, 0.03f);
    const glm::vec3 front = head.center() + glm::vec3(0.0f, 0.0f, 0.2f); // in front of the face
    for (int s = 0; s < 60; ++s) {
        const std::size_t i = frame->strands.addStrand(16);
        auto out = frame->strands.strandForWrite(i);
        for (int k = 0; k < 16; ++k)
            out[k] = front + glm::vec3(-0.03f + 0.001f * s, 0.03f - 0.004f * k, 0.0f);
        out[s % 16]
            = glm::vec3(s % 2 ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity());
    }
    viewport->setFrame(frame);
    const QImage image = grab();
    const glm::vec2 sheet = viewport->project(front);
    EXPECT_EQ(countPixels(image, isGreenHair, around(sheet, 12)), 0);
    const glm::vec2 lock = viewport->project(lockTop(head) - glm::vec3(0.0f, 0.5f * kLockLength, 0.0f));
    EXPECT_GE(countPixels(image, isGreenHair, around(lock, 2)), 15);

    // Offsets that point past the points: nothing drawn, nothing read out of bounds.
    auto broken = std::make_shared<Frame>(*lockFrame(head));
    broken->strands.offsets.push_back(broken->strands.offsets.back() + 1000);
    viewport->setFrame(broken);
    EXPECT_EQ(countPixels(grab(), isGreenHair, around(lock, 4)), 0);

    // And back to a good frame of another layout.
    viewport->setFrame(lockFrame(head, 50));
    EXPECT_GE(countPixels(grab(), isGreenHair, around(lock, 2)), 10);
}

TEST_F(ViewportTest, SurvivesANewContextAndAnUnusableHead)
{
    // Moving the widget into another window gives it a new GL context: everything is uploaded again.
    viewport->setFrame(lockFrame(head));
    grab();
    {
        const ViewportInNewWindow newWindow(*viewport);
        ASSERT_TRUE(newWindow.exposed());
        const QImage moved = grab();
        EXPECT_EQ(countPixels(moved, isSkin, around(viewport->project(head.center()), 2)), 25);
        const glm::vec2 lock = viewport->project(lockTop(head) - glm::vec3(0.0f, 0.5f * kLockLength, 0.0f));
        EXPECT_GE(countPixels(moved, isGreenHair, around(lock, 2)), 15);
    }

    // A head that cannot be drawn (an index out of range, a NaN) draws nothing, and framing falls
    // back to an average head's size.
    TriangleMesh broken = defaultHead().mesh;
    broken.triangles.push_back({ 0u, 1u, 999999999u });
    viewport->setHead(broken);
    viewport->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(viewport.get()));
    EXPECT_EQ(skinPixels(grab()), 0);
    TriangleMesh empty;
    viewport->setHead(empty);
    viewport->frameHead();
    EXPECT_EQ(skinPixels(grab()), 0);
    EXPECT_TRUE(std::isfinite(viewport->camera().distance()));
    viewport->setHead(defaultHead().mesh);
    EXPECT_GT(skinPixels(grab()), 640 * 480 / 10);
}

TEST_F(ViewportTest, GridAndWindArrowAreShownAndHidden)
{
    EXPECT_TRUE(viewport->showGrid());
    const QImage withGrid = grab();
    viewport->setShowGrid(false);
    EXPECT_FALSE(viewport->showGrid());
    const QImage withoutGrid = grab();
    EXPECT_GT(differingPixels(withGrid, withoutGrid), 500);
    // The top of the view, above the head, shows sky: no grid there.
    EXPECT_EQ(differingPixels(withGrid.copy(0, 0, 640, 110), withoutGrid.copy(0, 0, 640, 110)), 0);

    // The wind is a small indicator right of the axis gizmo, in the bottom-left corner: nothing else
    // of the view changes with it, so it never covers the head or the hair.
    const glm::vec3 wind{ -8.0f, 0.0f, 0.0f };
    viewport->setWind(wind);
    const QImage withWind = grab();
    const QRect corner(kGizmoImageSize, 480 - kGizmoImageSize, kWindIndicatorWidth, kGizmoImageSize);
    EXPECT_GE(countPixels(withWind, isWindBlue, corner), 30);
    EXPECT_EQ(countPixels(withoutGrid, isWindBlue, corner), 0);
    QImage outside = withWind;
    QImage outsideBefore = withoutGrid;
    for (QImage* image : { &outside, &outsideBefore })
        for (int y = corner.top(); y <= corner.bottom(); ++y)
            for (int x = 0; x <= corner.right(); ++x)
                image->setPixelColor(x, y, Qt::black);
    EXPECT_EQ(differingPixels(outside, outsideBefore), 0);

    // Still air hides it; a frame's wind shows it again.
    viewport->setWind(glm::vec3(0.0f));
    EXPECT_EQ(differingPixels(grab(), withoutGrid), 0);
    auto frame = std::make_shared<Frame>();
    frame->wind = wind;
    viewport->setFrame(frame);
    EXPECT_GE(countPixels(grab(), isWindBlue, corner), 30);
}

TEST_F(ViewportTest, HairThicknessWidensTheStrands)
{
    // A region's hair thickness (Param::HairThickness, carried by its look) sets the drawn width:
    // four times as thick covers clearly more of the view.
    viewport->setLevelOfDetail(false);
    viewport->setShadowsEnabled(false);
    const auto drawnWith = [&](float thicknessMetres) {
        auto frame = lockFrame(head, 40);
        StrandLook green;
        green.rootColour = green.tipColour = glm::vec3(40 / 255.0f, 235 / 255.0f, 40 / 255.0f);
        green.rootThicknessMetres = thicknessMetres;
        frame->looks.push_back(green);
        frame->lookOfStrand.assign(frame->strands.strandCount(), 0);
        viewport->setFrame(frame);
        return countPixels(grab(), isGreenHair);
    };
    const int thin = drawnWith(static_cast<float>(parameterInfo(Param::HairThickness).defaultValue));
    const int thick = drawnWith(4.0f * static_cast<float>(parameterInfo(Param::HairThickness).defaultValue));
    std::printf("[ viewport ] green pixels: %d at the default thickness, %d at four times it\n", thin, thick);
    EXPECT_GT(thin, 100);
    EXPECT_GT(thick, thin * 5 / 4); // the lock's strands overlap more as they widen
}

// Issue 14's "thin hair draws smoothly". Failed while the hair was drawn into the 4x MSAA frame (13
// of 976 samples missed at a 0.39-pixel root: a 1-pixel line spread its alpha over the samples it
// covered, and a low-coverage strand dropped out where it straddled pixels); the hair is now drawn
// single-sampled with its coverage in alpha.
TEST_F(ViewportTest, AThinStrandStaysAContinuousLineWhileTheViewOrbits)
{
    // One strand seen from afar is narrower than a pixel: it is drawn a pixel wide with its
    // coverage as alpha, so along its projected curve every sample has some of it, in each of 16
    // consecutive frames of a slow orbit (no gaps, no crawling stair-steps that drop out). Its root
    // half: toward the tip it tapers and fades below a tenth of a pixel, which the tip fade means.
    viewport->setLevelOfDetail(false);
    const FramePtr frame = lockFrame(head, 1);
    viewport->setFrame(frame);
    for (int k = 0; k < 4; ++k)
        wheel(viewport.get(), -120); // zoom out
    // The strand itself (a one-strand lock is rooted off the lock's centre, about two pixels here).
    const auto strand = frame->strands.strand(0);
    const glm::vec3 top = strand.front();
    const glm::vec3 bottom = strand.back();
    const RenderViewProbe probe = probeWidth(*viewport, top);
    std::printf("[ viewport ] the strand's root is %.2f pixels wide\n", probe.rootPixels);
    EXPECT_LT(probe.rootPixels, 1.0f);
    int gaps = 0;
    int samples = 0;
    double leastInk = 1e9;
    double mostInk = 0.0;
    for (int step = 0; step < 16; ++step) {
        viewport->camera().orbit(2.0f, 0.0f); // a few tenths of a degree per frame
        const QImage image = grab();
        if (step == 0)
            saveScreenshot(image, "viewport-thin-strand.png");
        for (int s = 0; s <= 60; ++s) {
            const glm::vec2 p = viewport->project(glm::mix(top, bottom, 0.05f + 0.45f * static_cast<float>(s) / 60.0f));
            const QColor background = Viewport::backgroundColour((p.y + 0.5) / image.height());
            const int touched = countPixels(
                image, [&](QColor c) { return !near(c, background, 10); }, around(p, 1));
            ++samples;
            gaps += touched > 0 ? 0 : 1;
            // The strand's ink in the 3x3 pixels around the sample (green over the background: the
            // lock's colour): a crawling, stair-stepping line would gain and lose it along the way.
            double ink = 0.0;
            const QRect box = around(p, 1);
            for (int y = box.top(); y <= box.bottom(); ++y)
                for (int x = box.left(); x <= box.right(); ++x)
                    ink += std::max(0, image.pixelColor(x, y).green() - background.green());
            leastInk = std::min(leastInk, ink);
            mostInk = std::max(mostInk, ink);
        }
    }
    std::printf("[ viewport ] thin strand: %d gaps in %d samples; ink per 3x3 window %.0f to %.0f\n", gaps, samples,
        leastInk, mostInk);
    EXPECT_EQ(samples, 16 * 61);
    EXPECT_EQ(gaps, 0);
    EXPECT_LT(mostInk, 2.0 * leastInk); // even along the strand and across frames
}

TEST_F(ViewportTest, HudSaysPausedWhilePaused)
{
    viewport->setFrame(lockFrame(head));
    grab();
    EXPECT_TRUE(viewport->hudText().startsWith(QStringLiteral("fps ")));
    viewport->setPaused(true);
    const QImage paused = grab();
    EXPECT_EQ(viewport->hudText(), QStringLiteral("paused · 120 strands · 1920 particles"));
    viewport->setPaused(false);
    const QImage playing = grab();
    EXPECT_TRUE(viewport->hudText().startsWith(QStringLiteral("fps ")));
    // What the HUD shows is what it says: its pixels change with it.
    int changed = 0;
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 400; ++x)
            changed += near(paused.pixelColor(x, y), playing.pixelColor(x, y), 8) ? 0 : 1;
    EXPECT_GT(changed, 50);
}

TEST_F(ViewportTest, RayAtIsTheInverseOfProject)
{
    const auto checkRoundTrip = [&](const glm::vec3& point) {
        const glm::vec2 pixel = viewport->project(point);
        const ViewRay ray = viewport->rayAt(QPointF(pixel.x, pixel.y));
        EXPECT_NEAR(glm::length(ray.direction), 1.0f, 1e-5f);
        EXPECT_LT(glm::length(ray.origin - viewport->camera().eye()), 1e-5f);
        EXPECT_GT(glm::dot(point - ray.origin, ray.direction), 0.0f); // ahead, not behind
        const float missMetres = glm::length(glm::cross(point - ray.origin, ray.direction));
        EXPECT_LT(missMetres, 1e-4f) << point.x << ", " << point.y << ", " << point.z;
    };
    const std::vector<glm::vec3> points{ head.center(), head.max, head.min + glm::vec3(0.01f, 0.0f, 0.0f),
        lockTop(head), defaultHead().mesh.positions[defaultHead().mesh.positions.size() / 3] };
    for (const glm::vec3& p : points)
        checkRoundTrip(p);
    // Off the middle of the view, after orbiting, panning and zooming.
    drag(viewport.get(), Qt::MiddleButton, Qt::NoModifier, { 300, 240 }, { 210, 300 });
    drag(viewport.get(), Qt::MiddleButton, Qt::ShiftModifier, { 300, 240 }, { 350, 200 });
    wheel(viewport.get(), 240);
    for (const glm::vec3& p : points)
        checkRoundTrip(p);
    // The middle of the view looks along the camera's axis.
    const ViewRay middle = viewport->rayAt(QPointF(viewport->width() / 2.0, viewport->height() / 2.0));
    EXPECT_NEAR(glm::dot(middle.direction, viewport->camera().forward()), 1.0f, 1e-6f);
}

} // namespace
