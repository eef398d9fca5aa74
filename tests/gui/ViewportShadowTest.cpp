// The viewport's hair shadows and two-pass ribbons.
#include "ViewportTestSupport.h"

using namespace wisp;
using namespace wisp::test;

namespace {

// The editor's default scene: the default head's painted scalp with the registry's default
// parameters, hanging at rest under gravity (once per run).
FramePtr defaultSceneFrame()
{
    static const FramePtr frame = [] {
        HairSimulation simulation(1);
        const std::string error = simulation.setup(defaultHead().mesh, defaultHead().growthWeights, ParameterValues());
        EXPECT_EQ(error, "");
        simulation.drapeAtRest(200);
        auto out = std::make_shared<Frame>();
        simulation.buildFrame(out->strands);
        out->simulatedStrands = out->strands.strandCount();
        out->simulatedParticles = out->strands.pointCount();
        return FramePtr(out);
    }();
    return frame;
}

// Ribbons at full detail are drawn in two passes (each spline sample evaluated and shaded once,
// captured by transform feedback, then both edges drawn from it; HairRenderer): the image is the
// one-pass image (WISP_ONE_PASS_RIBBONS), a close-up of the crown where the strands are ribbons
// several pixels wide.
TEST_F(ViewportTest, RibbonsInTwoPassesDrawWhatOnePassDraws)
{
    const FramePtr scene = defaultSceneFrame();
    Viewport::ImageOptions options;
    const glm::vec3 top{ head.center().x, head.max.y, head.center().z };
    options.frameBounds = Aabb{ top - glm::vec3(0.03f), top + glm::vec3(0.03f) };
    const QSize size(320, 320);
    viewport->setLevelOfDetail(false);
    viewport->setFrame(scene);
    const QImage twoPasses = viewport->renderImage(size, options).convertToFormat(QImage::Format_RGB32);

    qputenv("WISP_ONE_PASS_RIBBONS", "1"); // read when a viewport's GL starts
    Viewport reference;
    reference.resize(640, 480);
    reference.setHead(defaultHead().mesh);
    reference.setHairColours(QColor(40, 235, 40), QColor(40, 235, 40));
    reference.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&reference));
    reference.setLevelOfDetail(false);
    reference.setFrame(scene);
    const QImage onePass = reference.renderImage(size, options).convertToFormat(QImage::Format_RGB32);
    qunsetenv("WISP_ONE_PASS_RIBBONS");
    ASSERT_EQ(twoPasses.size(), size);
    ASSERT_EQ(onePass.size(), size);

    int hair = 0; // the fixture's green hair, so the comparison is not of two empty images
    int differing = 0; // any channel more than 3 levels apart
    for (int y = 0; y < size.height(); ++y)
        for (int x = 0; x < size.width(); ++x) {
            const QColor a = twoPasses.pixelColor(x, y);
            const QColor b = onePass.pixelColor(x, y);
            hair += a.green() > a.red() + 40 ? 1 : 0;
            const int d = std::max(
                { std::abs(a.red() - b.red()), std::abs(a.green() - b.green()), std::abs(a.blue() - b.blue()) });
            differing += d > 3 ? 1 : 0;
        }
    std::printf(
        "[ viewport ] close-up ribbons: %d hair pixels, %d differ between two passes and one\n", hair, differing);
    EXPECT_GT(hair, size.width() * size.height() / 10);
    EXPECT_LE(differing, size.width() * size.height() / 500);
}

double luminance(QColor c)
{
    return 0.2126 * c.redF() + 0.7152 * c.greenF() + 0.0722 * c.blueF();
}

// The default scene's size of hair over the crown, at 640x640: with shadows, at least a tenth of
// what is not background is a fifth darker or more (issue 14), and skin under the hair's shadow is
// darker than the same skin (same point, same normal) without it, while skin the hair does not
// shade keeps its colour.
TEST_F(ViewportTest, ShadowsDarkenTheHairAndTheSkinUnderIt)
{
    viewport->resize(640, 640);
    viewport->frameHead();
    viewport->setLevelOfDetail(false); // both images of every strand
    viewport->setBody(defaultBody(defaultHead().mesh));
    viewport->setHairColours(QColor(60, 40, 25), QColor(130, 90, 50)); // the editor's browns
    const FramePtr scene = defaultSceneFrame();
    ASSERT_GT(scene->strands.strandCount(), 3000u);
    viewport->setFrame(scene);
    EXPECT_TRUE(viewport->shadowsEnabled()); // the default
    viewport->setShadowsEnabled(false);
    const QImage off = grab();
    viewport->setShadowsEnabled(true);
    const QImage on = grab();
    saveScreenshot(off, "viewport-shadows-off.png");
    saveScreenshot(on, "viewport-shadows-on.png");
    ASSERT_EQ(off.size(), QSize(640, 640));

    int content = 0;
    int darker = 0;
    int skin = 0;
    int shadedSkin = 0;
    for (int y = 40; y < off.height(); ++y) {
        const QColor background = Viewport::backgroundColour((y + 0.5) / off.height());
        for (int x = 0; x < off.width(); ++x) {
            if (x < 110 && y > off.height() - 110)
                continue; // the axis gizmo
            const QColor a = off.pixelColor(x, y);
            const QColor b = on.pixelColor(x, y);
            if (near(a, background, 6))
                continue;
            ++content;
            const bool shaded = luminance(b) <= 0.8 * luminance(a);
            darker += shaded ? 1 : 0;
            if (isSkin(a)) {
                ++skin;
                shadedSkin += shaded ? 1 : 0;
            }
        }
    }
    std::printf("[ viewport ] shadows: %d of %d non-background pixels at least 20%% darker; %d of %d skin pixels\n",
        darker, content, shadedSkin, skin);
    ASSERT_GT(content, 640 * 640 / 10);
    EXPECT_GE(darker, content / 10);
    EXPECT_GE(shadedSkin, 500); // the hair's shadow on the skin
    // The face, which no hair covers or shades from the key light, keeps its colour.
    const QRect face = around(viewport->project(head.center() + glm::vec3(0.0f, 0.0f, 0.5f * head.size().z)), 2);
    ASSERT_EQ(countPixels(off, isSkin, face), 25);
    EXPECT_EQ(differingPixels(off.copy(face), on.copy(face)), 0);

    // The hair's shadow on the head, against the same skin without hair: the skin under the crown's
    // hair, where it shows between the strands, is darker with the hair there than without it.
    viewport->setFrame(nullptr);
    const QImage bare = grab();
    int underHair = 0;
    int underHairDarker = 0;
    for (int y = 40; y < on.height(); ++y)
        for (int x = 110; x < on.width(); ++x)
            if (isSkin(bare.pixelColor(x, y)) && isSkin(off.pixelColor(x, y))
                && off.pixelColor(x, y) == bare.pixelColor(x, y)) {
                ++underHair;
                underHairDarker += luminance(on.pixelColor(x, y)) < 0.9 * luminance(bare.pixelColor(x, y)) ? 1 : 0;
            }
    std::printf("[ viewport ] skin not covered by hair: %d pixels, %d of them darker in the hair's shadow\n", underHair,
        underHairDarker);
    EXPECT_GE(underHairDarker, 500);
}

// On a software GL the shadow map's hair passes are drawn on the CPU (HairShadowRaster.h): the
// default scene's image with them is the image with GL's passes, to a level or two at the
// shadows' edges.
TEST_F(ViewportTest, TheShadowMapsHairDrawnOnTheCpuShadesAsGlsDoes)
{
    viewport->resize(640, 640);
    viewport->frameHead();
    viewport->setLevelOfDetail(false);
    viewport->setHairColours(QColor(60, 40, 25), QColor(130, 90, 50));
    viewport->setFrame(defaultSceneFrame());
    grab();
    viewport->setSoftwareShadowHair(true);
    const std::uint64_t passes = viewport->shadowPassCount();
    const QImage onCpu = grab();
    EXPECT_EQ(viewport->shadowPassCount(), passes + 1);
    viewport->setSoftwareShadowHair(false);
    const QImage byGl = grab();
    viewport->setShadowsEnabled(false);
    const QImage unshaded = grab();
    ASSERT_EQ(onCpu.size(), byGl.size());
    double difference = 0.0; // mean over the pixels, luminance 0..1
    double shading = 0.0; // how much the shadows change the image, the same way
    int apart = 0; // pixels more than 8 levels apart
    for (int y = 0; y < onCpu.height(); ++y)
        for (int x = 0; x < onCpu.width(); ++x) {
            difference += std::abs(luminance(onCpu.pixelColor(x, y)) - luminance(byGl.pixelColor(x, y)));
            shading += std::abs(luminance(byGl.pixelColor(x, y)) - luminance(unshaded.pixelColor(x, y)));
            apart += std::abs(qGray(onCpu.pixel(x, y)) - qGray(byGl.pixel(x, y))) > 8 ? 1 : 0;
        }
    const double pixels = static_cast<double>(onCpu.width()) * onCpu.height();
    std::printf("[ viewport ] shadow map's hair on the CPU against GL: mean difference %.4f (the shadows themselves "
                "%.4f), %d pixels more than 8 levels apart\n",
        difference / pixels, shading / pixels, apart);
    EXPECT_GT(shading / pixels, 0.01); // there are shadows to compare
    EXPECT_LT(difference, 0.1 * shading);
    EXPECT_LT(apart, static_cast<int>(pixels / 100));
}

TEST_F(ViewportTest, OrbitingAPausedSceneReusesTheShadowsAndMovingHairRendersThem)
{
    viewport->setFrame(scalpFrame(head, 600, 16, 0.0f));
    grab();
    const std::uint64_t passes = viewport->shadowPassCount();
    EXPECT_GE(passes, 1u);
    // The head's light per vertex is looked up once for these shadows, not once a paint.
    const std::uint64_t lookups = viewport->headLightLookups();
    EXPECT_GE(lookups, 1u);
    for (int k = 0; k < 4; ++k) {
        drag(viewport.get(), Qt::MiddleButton, Qt::NoModifier, { 300, 240 }, { 320, 240 });
        grab();
    }
    EXPECT_EQ(viewport->shadowPassCount(), passes); // the key light stays with the head
    EXPECT_EQ(viewport->headLightLookups(), lookups);
    viewport->setFrame(scalpFrame(head, 600, 16, 1.0f));
    grab();
    EXPECT_EQ(viewport->shadowPassCount(), passes + 1);
    EXPECT_EQ(viewport->headLightLookups(), lookups + 1); // the head takes the new shadow
    // A light that follows the camera renders them again as the camera turns.
    viewport->setLightFollowsCamera(true);
    grab();
    const std::uint64_t following = viewport->shadowPassCount();
    const std::uint64_t followingLookups = viewport->headLightLookups();
    drag(viewport.get(), Qt::MiddleButton, Qt::NoModifier, { 300, 240 }, { 340, 240 });
    grab();
    EXPECT_EQ(viewport->shadowPassCount(), following + 1);
    EXPECT_EQ(viewport->headLightLookups(), followingLookups + 1);
    // Off: none rendered, and the head is lit fully once, then left alone.
    viewport->setShadowsEnabled(false);
    viewport->setFrame(scalpFrame(head, 600, 16, 2.0f));
    grab();
    EXPECT_EQ(viewport->shadowPassCount(), following + 1);
    EXPECT_EQ(viewport->headLightLookups(), followingLookups + 2);
    drag(viewport.get(), Qt::MiddleButton, Qt::NoModifier, { 300, 240 }, { 340, 240 });
    grab();
    EXPECT_EQ(viewport->headLightLookups(), followingLookups + 2);
}

// While the hair moves (frames streaming in, not grabbed), the shadow maps are rendered every third
// paint: the key light is fixed to the head, and each render costs a software rasteriser about a
// fifth of a simulating paint. Every other paint rendered them before.
TEST_F(ViewportTest, WhileTheHairMovesItsShadowsAreRenderedEveryThirdPaint)
{
    viewport->setFrame(scalpFrame(head, 600, 16, 0.0f));
    grab();
    const std::uint64_t passes = viewport->shadowPassCount();
    const std::uint64_t paints = viewport->paintCount();
    for (int k = 1; k <= 9; ++k) {
        viewport->setFrame(scalpFrame(head, 600, 16, static_cast<float>(k)));
        viewport->repaint();
    }
    ASSERT_EQ(viewport->paintCount(), paints + 9);
    EXPECT_EQ(viewport->shadowPassCount(), passes + 3);
}

} // namespace

// Frames arriving as the simulation sends them, slower than the view can paint: each paint is a new
// frame's, at half resolution, and none comes between them. A skipped shadow render used to ask for
// a paint at once to catch up; it came before the next frame, found nothing moving and drew
// everything at full resolution (in the editor every third paint, 75-90 ms of 110). Once the frames
// stop, the refinement paint draws the shadows of the last frame.
TEST_F(ViewportTest, StreamedFramesArePaintedOnceEachAndTheStillPaintCatchesUpTheShadows)
{
    // The frames come as fast as this test makes them, which a loaded machine may slow past the
    // refinement's delay: it waits, here, until the frames have stopped.
    viewport->setRefineDelayMs(3'600'000);
    viewport->setFrame(scalpFrame(head, 600, 16, 0.0f));
    grab();
    const std::uint64_t passes = viewport->shadowPassCount();
    const std::uint64_t paints = viewport->paintCount();
    constexpr int kFrames = 7; // shadows at the third and sixth; the seventh's skipped
    for (int k = 1; k <= kFrames; ++k) {
        viewport->setFrame(scalpFrame(head, 600, 16, static_cast<float>(k)));
        ASSERT_TRUE(test::waitUntil([&] { return viewport->paintCount() >= paints + static_cast<std::uint64_t>(k); }));
        ASSERT_EQ(viewport->paintCount(), paints + static_cast<std::uint64_t>(k)) << "frame " << k;
        for (int turn = 0; turn < 5; ++turn) // a paint asked for at once would happen here
            QCoreApplication::processEvents();
        EXPECT_EQ(viewport->paintCount(), paints + static_cast<std::uint64_t>(k)) << "after frame " << k;
        if (viewport->halfResolutionWhileMoving()) {
            EXPECT_TRUE(viewport->lastPaintHairAtHalfResolution()) << "frame " << k;
        }
    }
    EXPECT_EQ(viewport->shadowPassCount(), passes + 2);
    // Still: the refinement paint renders the last frame's shadows.
    viewport->setRefineDelayMs(0);
    ASSERT_TRUE(test::waitUntil([&] { return viewport->shadowPassCount() == passes + 3; }));
    EXPECT_EQ(viewport->paintCount(), paints + kFrames + 1);
    if (viewport->halfResolutionWhileMoving()) {
        EXPECT_FALSE(viewport->lastPaintHairAtHalfResolution());
    }
}
