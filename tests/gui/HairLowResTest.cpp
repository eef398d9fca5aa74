// The hair at half resolution while the camera or the hair moves (HairLowResTarget): the same
// coverage and colour as at full resolution, hair behind the head kept behind it, and a still view
// drawn whole. The scene is the editor's default groom, draped, in its default view.

#include "SettledViewportTest.h"
#include "ViewportTestSupport.h"

#include "app/editor/Document.h"
#include "app/editor/SettledScene.h"
#include "sim/geometry/Body.h"
#include "widgets/Viewport.h"

#include "widgets/HairLowResTarget.h"

#include <QImage>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

namespace wisp {
namespace {

class HairLowResTest : public test::SettledViewportTest {
protected:
    static int difference(QRgb a, QRgb b)
    {
        return std::abs(qRed(a) - qRed(b)) + std::abs(qGreen(a) - qGreen(b)) + std::abs(qBlue(a) - qBlue(b));
    }
    static constexpr QSize kSize{ 585, 710 };
    // What the hair adds to the bare view: its ink (how far it moves each pixel from the bare head,
    // summed, R+G+B levels), the pixels it changes by more than 24 levels, and their mean colour.
    struct Ink {
        double ink = 0.0;
        qint64 covered = 0;
        double sum[3] = {};
        double mean(int channel) const { return covered > 0 ? sum[channel] / static_cast<double>(covered) : 0.0; }
    };
    static Ink inkOver(const QImage& image, const QImage& bare)
    {
        Ink result;
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) {
                const QRgb b = bare.pixel(x, y);
                const QRgb c = image.pixel(x, y);
                result.ink += difference(c, b);
                if (difference(c, b) > 24) {
                    ++result.covered;
                    result.sum[0] += qRed(c);
                    result.sum[1] += qGreen(c);
                    result.sum[2] += qBlue(c);
                }
            }
        return result;
    }
    // The default view without hair, with it, and with it drawn as `options` ask.
    struct Images {
        QImage bare, full, variant;
    };
    Images renderImages(const Viewport::ImageOptions& options)
    {
        Images images;
        viewport->setFrame(nullptr);
        images.bare = viewport->renderImage(kSize);
        viewport->setFrame(settled->frame);
        images.full = viewport->renderImage(kSize);
        images.variant = viewport->renderImage(kSize, options);
        return images;
    }
};

TEST_F(HairLowResTest, HalfResolutionHairKeepsTheCoverageAndColourAndStaysBehindTheHead)
{
    const QSize size = kSize;
    Viewport::ImageOptions halfOptions;
    halfOptions.hairAtHalfResolution = true;
    const auto [bare, full, half] = renderImages(halfOptions);
    if (const QString shots = qEnvironmentVariable("WISP_SCREENSHOT_DIR"); !shots.isEmpty()) {
        full.save(shots + QStringLiteral("/hair-full-resolution.png"));
        half.save(shots + QStringLiteral("/hair-half-resolution.png"));
    }
    ASSERT_EQ(full.size(), size);
    ASSERT_EQ(half.size(), size);

    // Ink: how far the hair moves each pixel from the bare head, summed (R+G+B levels). Blending
    // "over" into the half-resolution target and spreading it bilinearly keeps it; a strand drawn
    // twice as opaque, or lost to a wrong depth, would not.
    double fullInk = 0.0;
    double halfInk = 0.0;
    // Where the hair shows, its colour: the mean of each channel over pixels it changes by more
    // than 24 levels, in both images.
    double fullSum[3] = {};
    double halfSum[3] = {};
    qint64 fullCovered = 0;
    qint64 halfCovered = 0;
    // The face: skin the full-resolution hair leaves exactly as it was, two pixels around. Hair
    // behind the head drawn over it there would be the half-resolution image's depth test failing.
    const auto untouchedAround = [&](int x, int y) {
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
                const int u = std::clamp(x + dx, 0, size.width() - 1);
                const int v = std::clamp(y + dy, 0, size.height() - 1);
                if (full.pixel(u, v) != bare.pixel(u, v))
                    return false;
            }
        return true;
    };
    qint64 bareSkin = 0;
    qint64 bareSkinChanged = 0;
    for (int y = 0; y < size.height(); ++y)
        for (int x = 0; x < size.width(); ++x) {
            const QRgb b = bare.pixel(x, y);
            const QRgb f = full.pixel(x, y);
            const QRgb h = half.pixel(x, y);
            fullInk += difference(f, b);
            halfInk += difference(h, b);
            if (difference(f, b) > 24) {
                ++fullCovered;
                fullSum[0] += qRed(f);
                fullSum[1] += qGreen(f);
                fullSum[2] += qBlue(f);
            }
            if (difference(h, b) > 24) {
                ++halfCovered;
                halfSum[0] += qRed(h);
                halfSum[1] += qGreen(h);
                halfSum[2] += qBlue(h);
            }
            if (test::isSkin(QColor(b)) && untouchedAround(x, y)) {
                ++bareSkin;
                bareSkinChanged += difference(h, b) > 24;
            }
        }
    ASSERT_GT(fullCovered, 0);
    ASSERT_GT(halfCovered, 0);
    std::printf("[ half-res ] ink %.0f full, %.0f half (%.3f); covered pixels %lld full, %lld half; mean colour "
                "(%.1f %.1f %.1f) full, (%.1f %.1f %.1f) half; bare skin %lld, changed by the half-resolution "
                "hair %lld\n",
        fullInk, halfInk, halfInk / fullInk, static_cast<long long>(fullCovered), static_cast<long long>(halfCovered),
        fullSum[0] / fullCovered, fullSum[1] / fullCovered, fullSum[2] / fullCovered, halfSum[0] / halfCovered,
        halfSum[1] / halfCovered, halfSum[2] / halfCovered, static_cast<long long>(bareSkin),
        static_cast<long long>(bareSkinChanged));
    // A little more: at full resolution a strand in front hides the strands drawn after it in its
    // pixel (depth written), at half resolution nothing does (HairLowResTarget.h). Measured 1.10, 1.11.
    EXPECT_NEAR(halfInk / fullInk, 1.0, 0.15);
    EXPECT_NEAR(static_cast<double>(halfCovered) / static_cast<double>(fullCovered), 1.0, 0.15);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(halfSum[c] / halfCovered, fullSum[c] / fullCovered, 6.0) << c;
    ASSERT_GT(bareSkin, 5000);
    EXPECT_LT(static_cast<double>(bareSkinChanged), 0.01 * static_cast<double>(bareSkin));
}

// While the camera moves, the hair at half resolution and the backdrop single-sampled; the still
// view's paint after it draws both whole, and each switch works on its own.
TEST_F(HairLowResTest, AnOrbitDrawsTheHairAtHalfResolutionAndTheStillViewWhole)
{
    viewport->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(viewport.get()));
    viewport->setLevelOfDetail(false);
    viewport->setHalfResolutionWhileMoving(true);
    viewport->setSingleSampledBackdropWhileMoving(true);
    viewport->repaint(); // a first frame: the camera, the hair and the backdrop are new
    ASSERT_GT(viewport->samples(), 0) << "the view multisamples its backdrop";
    for (int i = 0; i < 3; ++i) {
        viewport->camera().orbit(6.0f, 0.0f);
        viewport->repaint();
        EXPECT_TRUE(viewport->lastPaintHairAtHalfResolution()) << i;
        EXPECT_TRUE(viewport->lastPaintBackdropSingleSampled()) << i;
    }
    // Once the camera stops, one paint draws it all whole (a bounded wait).
    const std::uint64_t paints = viewport->paintCount();
    EXPECT_TRUE(test::waitUntil(
        [&] { return !viewport->lastPaintHairAtHalfResolution() && !viewport->lastPaintBackdropSingleSampled(); }));
    EXPECT_GT(viewport->paintCount(), paints);
    // A grab is the still view's frame, however it came.
    viewport->camera().orbit(6.0f, 0.0f);
    viewport->grabFramebuffer();
    EXPECT_FALSE(viewport->lastPaintHairAtHalfResolution());
    EXPECT_FALSE(viewport->lastPaintBackdropSingleSampled());
    // Each switched off on its own.
    viewport->setHalfResolutionWhileMoving(false);
    viewport->camera().orbit(6.0f, 0.0f);
    viewport->repaint();
    EXPECT_FALSE(viewport->lastPaintHairAtHalfResolution());
    EXPECT_TRUE(viewport->lastPaintBackdropSingleSampled());
    viewport->setSingleSampledBackdropWhileMoving(false);
    viewport->camera().orbit(6.0f, 0.0f);
    viewport->repaint();
    EXPECT_FALSE(viewport->lastPaintBackdropSingleSampled());
    // A new frame of the hair (it moves, the camera does not): the hair at half resolution again,
    // and the backdrop single-sampled too, as the hair's shadow on the head changes with it.
    viewport->setHalfResolutionWhileMoving(true);
    viewport->setSingleSampledBackdropWhileMoving(true);
    viewport->repaint(); // the camera's last move, settled
    EXPECT_FALSE(viewport->lastPaintBackdropSingleSampled());
    viewport->setFrame(std::make_shared<Frame>(*settled->frame));
    viewport->repaint();
    EXPECT_TRUE(viewport->lastPaintHairAtHalfResolution());
    EXPECT_EQ(viewport->lastPaintBackdropSingleSampled(), viewport->shadowsEnabled());
}

// The backdrop single-sampled, as an orbit paint draws it (Viewport::setSingleSampledBackdropWhileMoving):
// the same image but for the head's silhouette and the hair's edges, and the hair behind the head
// still hidden by it (the frame's own depth, not the resolved one).
TEST_F(HairLowResTest, ASingleSampledBackdropKeepsTheImageAndTheHeadInFront)
{
    const QSize size = kSize;
    Viewport::ImageOptions singleOptions;
    singleOptions.backdropSingleSampled = true;
    const auto [bare, full, single] = renderImages(singleOptions);
    if (const QString shots = qEnvironmentVariable("WISP_SCREENSHOT_DIR"); !shots.isEmpty())
        single.save(shots + QStringLiteral("/backdrop-single-sampled.png"));
    ASSERT_EQ(single.size(), size);
    const auto insideSkin = [&](int x, int y) {
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
                const int u = std::clamp(x + dx, 0, size.width() - 1);
                const int v = std::clamp(y + dy, 0, size.height() - 1);
                if (!test::isSkin(QColor(bare.pixel(u, v))) || full.pixel(u, v) != bare.pixel(u, v))
                    return false;
            }
        return true;
    };
    qint64 differ = 0;
    qint64 bareSkin = 0;
    qint64 bareSkinChanged = 0;
    for (int y = 0; y < size.height(); ++y)
        for (int x = 0; x < size.width(); ++x) {
            differ += difference(single.pixel(x, y), full.pixel(x, y)) > 24;
            // Skin inside the head's outline that the hair leaves as it was in the multisampled
            // image, two pixels around: untouched in this one too (edges differ by design).
            if (insideSkin(x, y)) {
                ++bareSkin;
                bareSkinChanged += difference(single.pixel(x, y), bare.pixel(x, y)) > 24;
            }
        }
    const double share = static_cast<double>(differ) / (static_cast<double>(size.width()) * size.height());
    std::printf("[ backdrop ] single-sampled: %.2f %% of pixels differ by more than 24 levels; bare skin %lld, "
                "changed %lld\n",
        100.0 * share, static_cast<long long>(bareSkin), static_cast<long long>(bareSkinChanged));
    EXPECT_GT(differ, 0); // it is single-sampled: the silhouette's edge pixels change
    EXPECT_LT(share, 0.02);
    ASSERT_GT(bareSkin, 5000);
    EXPECT_LT(static_cast<double>(bareSkinChanged), 0.005 * static_cast<double>(bareSkin));
}

// The software path (HairSoftwareRaster, HairShading; on by default on llvmpipe while the view
// moves): the CPU shades every sample as GL's vertex shader does, and its half-resolution hair has
// the ink and colour of GL's lines.
TEST_F(HairLowResTest, TheSoftwarePathShadesAndDrawsWhatGlDoes)
{
    viewport->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(viewport.get()));
    viewport->setLevelOfDetail(false);
    viewport->repaint();
    const std::vector<HairRasterSample> gl = viewport->shadedHairSamples(false);
    const std::vector<HairRasterSample> cpu = viewport->shadedHairSamples(true);
    ASSERT_GT(gl.size(), 10000u);
    ASSERT_EQ(cpu.size(), gl.size());
    float clipError = 0.0f;
    float colourError = 0.0f;
    float alphaError = 0.0f;
    float extentError = 0.0f;
    for (std::size_t i = 0; i < gl.size(); ++i) {
        for (int k = 0; k < 4; ++k)
            clipError = std::max(clipError, std::abs(gl[i].clip[k] - cpu[i].clip[k]) / std::abs(gl[i].clip.w));
        for (int k = 0; k < 3; ++k)
            colourError = std::max(colourError, std::abs(gl[i].colour[k] - cpu[i].colour[k]));
        alphaError = std::max(alphaError, std::abs(gl[i].colour.w - cpu[i].colour.w));
        extentError = std::max(extentError, std::abs(gl[i].side.z - cpu[i].side.z));
    }
    std::printf("[ software ] %zu samples: largest difference GL - CPU: clip %.2g (of w), colour %.2g, coverage %.2g, "
                "half extent %.2g pixels\n",
        gl.size(), clipError, colourError, alphaError, extentError);
    EXPECT_LT(clipError, 1e-5f);
    EXPECT_LT(colourError, 1.0f / 255.0f); // under one level of the 8-bit target
    EXPECT_LT(alphaError, 1e-4f);
    EXPECT_LT(extentError, 1e-4f);

    Viewport::ImageOptions halfOptions;
    halfOptions.hairAtHalfResolution = true;
    viewport->setFrame(nullptr);
    const QImage bare = viewport->renderImage(kSize);
    viewport->setFrame(settled->frame);
    const QImage onCpu = viewport->renderImage(kSize, halfOptions);
    viewport->setSoftwareHairWhileMoving(false);
    const QImage byGl = viewport->renderImage(kSize, halfOptions);
    viewport->setSoftwareHairWhileMoving(true);
    if (const QString shots = qEnvironmentVariable("WISP_SCREENSHOT_DIR"); !shots.isEmpty()) {
        onCpu.save(shots + QStringLiteral("/hair-half-resolution-cpu.png"));
        byGl.save(shots + QStringLiteral("/hair-half-resolution-gl.png"));
    }
    const Ink cpuHair = inkOver(onCpu, bare);
    const Ink glHair = inkOver(byGl, bare);
    ASSERT_GT(glHair.covered, 10000);
    ASSERT_GT(cpuHair.covered, 0);
    std::printf("[ software ] half-resolution hair: ink %.0f CPU, %.0f GL (%.3f); covered %lld CPU, %lld GL; mean "
                "colour (%.1f %.1f %.1f) CPU, (%.1f %.1f %.1f) GL\n",
        cpuHair.ink, glHair.ink, cpuHair.ink / glHair.ink, static_cast<long long>(cpuHair.covered),
        static_cast<long long>(glHair.covered), cpuHair.mean(0), cpuHair.mean(1), cpuHair.mean(2), glHair.mean(0),
        glHair.mean(1), glHair.mean(2));
    EXPECT_NEAR(cpuHair.ink / glHair.ink, 1.0, 0.1);
    EXPECT_NEAR(static_cast<double>(cpuHair.covered) / static_cast<double>(glHair.covered), 1.0, 0.1);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(cpuHair.mean(c), glHair.mean(c), 6.0) << c;
}

// Orbiting a paused scene shades the same captured samples from each new view: GL captures them
// once, not once a paint (the capture is the vertex shader's cost on llvmpipe's one vertex thread).
TEST_F(HairLowResTest, APausedOrbitCapturesTheHairOnceAndDrawsItOnTheCpu)
{
    viewport->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(viewport.get()));
    viewport->setLevelOfDetail(false);
    viewport->setHalfResolutionWhileMoving(true);
    viewport->setSoftwareHairWhileMoving(true);
    viewport->repaint();
    viewport->camera().orbit(6.0f, 0.0f);
    viewport->repaint();
    ASSERT_TRUE(viewport->lastPaintHairOnCpu());
    const std::uint64_t captures = viewport->hairWorldCaptures();
    EXPECT_GE(captures, 1u);
    for (int i = 0; i < 5; ++i) {
        viewport->camera().orbit(6.0f, 0.0f);
        viewport->repaint();
        EXPECT_TRUE(viewport->lastPaintHairAtHalfResolution()) << i;
        EXPECT_TRUE(viewport->lastPaintHairOnCpu()) << i;
        EXPECT_GT(viewport->lastDrawnStrands(), 1000u) << i;
    }
    EXPECT_EQ(viewport->hairWorldCaptures(), captures);
    // Off, GL's lines draw it.
    viewport->setSoftwareHairWhileMoving(false);
    viewport->camera().orbit(6.0f, 0.0f);
    viewport->repaint();
    EXPECT_TRUE(viewport->lastPaintHairAtHalfResolution());
    EXPECT_FALSE(viewport->lastPaintHairOnCpu());
}

// The hair laid over the frame by the pass that copies the frame out, only over where the CPU inked
// it (Viewport::setHalfResolutionHairInPresent, the default), against the blended pass of its own:
// the same image to a level (the "over" rounded to 8 bits once rather than twice).
TEST_F(HairLowResTest, TheHairLaidWhileCopyingTheFrameOutIsTheBlendedPassesImage)
{
    Viewport::ImageOptions halfOptions;
    halfOptions.hairAtHalfResolution = true;
    viewport->setFrame(nullptr);
    const QImage bare = viewport->renderImage(kSize);
    viewport->setFrame(settled->frame);
    viewport->setHalfResolutionHairInPresent(false);
    const QImage blended = viewport->renderImage(kSize, halfOptions);
    EXPECT_FALSE(viewport->lastPaintHairLaidInPresent());
    viewport->setHalfResolutionHairInPresent(true);
    const QImage laid = viewport->renderImage(kSize, halfOptions);
    EXPECT_TRUE(viewport->lastPaintHairLaidInPresent());
    ASSERT_EQ(laid.size(), kSize);
    ASSERT_EQ(blended.size(), kSize);
    const Ink ink = inkOver(laid, bare);
    const Ink blendedInk = inkOver(blended, bare);
    int largest = 0;
    qint64 apart = 0;
    for (int y = 0; y < kSize.height(); ++y)
        for (int x = 0; x < kSize.width(); ++x) {
            const QRgb a = laid.pixel(x, y);
            const QRgb b = blended.pixel(x, y);
            const int channel = std::max(
                { std::abs(qRed(a) - qRed(b)), std::abs(qGreen(a) - qGreen(b)), std::abs(qBlue(a) - qBlue(b)) });
            largest = std::max(largest, channel);
            apart += channel > 1;
        }
    std::printf("[ half-res ] laid while copying the frame out: ink %.0f (blended pass %.0f), largest channel "
                "difference %d, %lld pixels more than a level apart\n",
        ink.ink, blendedInk.ink, largest, static_cast<long long>(apart));
    ASSERT_GT(ink.covered, 20000); // the hair is there
    EXPECT_NEAR(ink.ink / blendedInk.ink, 1.0, 0.001);
    EXPECT_LE(largest, 2);
    EXPECT_LT(apart, 100);
}

// Where the CPU's half-resolution hair reaches the frame (HairLowResTarget::inkedSpans): every frame
// pixel whose bilinear read (lowres_hair.glsl's arithmetic, here on the CPU) takes an inked texel
// lies in a span, for even and odd frame sizes, and a single inked texel gives a span a few pixels
// wide.
TEST(HairLowResSpans, EveryFramePixelThatReadsInkLiesInASpanAndLittleElseDoes)
{
    for (const QSize frame : { QSize(160, 120), QSize(151, 97) }) {
        const QSize target = HairLowResTarget::sizeFor(frame);
        const PixelRect rect{ 3, 2, target.width() - 2, target.height() - 1 };
        const std::size_t w = static_cast<std::size_t>(rect.width());
        std::vector<std::uint8_t> rgba(4 * w * static_cast<std::size_t>(rect.height()), 0);
        const auto ink = [&](int x, int y, std::uint8_t value) {
            rgba[4 * (static_cast<std::size_t>(y - rect.y0) * w + static_cast<std::size_t>(x - rect.x0)) + 3] = value;
        };
        const auto inked = [&](int x, int y) {
            if (x < rect.x0 || x >= rect.x1 || y < rect.y0 || y >= rect.y1)
                return false;
            const std::size_t at
                = 4 * (static_cast<std::size_t>(y - rect.y0) * w + static_cast<std::size_t>(x - rect.x0));
            return rgba[at] != 0 || rgba[at + 1] != 0 || rgba[at + 2] != 0 || rgba[at + 3] != 0;
        };
        EXPECT_TRUE(HairLowResTarget::inkedSpans(rect, rgba, frame).empty());

        // One texel: a span or two (it may straddle two bands), a few pixels wide.
        ink(rect.x0 + 20, rect.y0 + 20, 9);
        std::vector<QRect> spans = HairLowResTarget::inkedSpans(rect, rgba, frame);
        ASSERT_GE(spans.size(), 1u);
        EXPECT_LE(spans.size(), 2u);
        for (const QRect& span : spans) {
            EXPECT_LE(span.width(), 10);
            EXPECT_EQ(span.height() % HairLowResTarget::kSpanRows == 0 || span.bottom() == frame.height() - 1, true);
        }
        // Texels scattered over the rectangle, the edges among them.
        std::mt19937 random(11);
        for (int k = 0; k < 30; ++k)
            ink(rect.x0 + static_cast<int>(random() % w), rect.y0 + static_cast<int>(random() % rect.height()), 40);
        ink(rect.x0, rect.y0, 1);
        ink(rect.x1 - 1, rect.y1 - 1, 200);
        spans = HairLowResTarget::inkedSpans(rect, rgba, frame);
        const double rx = static_cast<double>(target.width()) / frame.width();
        const double ry = static_cast<double>(target.height()) / frame.height();
        int missed = 0;
        for (int y = 0; y < frame.height(); ++y)
            for (int x = 0; x < frame.width(); ++x) {
                const int bx = static_cast<int>(std::floor((x + 0.5) * rx - 0.5));
                const int by = static_cast<int>(std::floor((y + 0.5) * ry - 0.5));
                bool reads = false;
                for (int k = 0; k < 4; ++k) {
                    const int tx = std::clamp(bx + (k & 1), 0, target.width() - 1);
                    const int ty = std::clamp(by + (k >> 1), 0, target.height() - 1);
                    reads = reads || inked(tx, ty);
                }
                const bool covered
                    = std::any_of(spans.begin(), spans.end(), [&](const QRect& span) { return span.contains(x, y); });
                missed += reads && !covered;
            }
        EXPECT_EQ(missed, 0) << frame.width() << "x" << frame.height();
        // Bands apart, bottom up, as FrameCompositor::draw takes them.
        for (std::size_t i = 1; i < spans.size(); ++i)
            EXPECT_GE(spans[i].top(), spans[i - 1].bottom() + 1);
    }
}

} // namespace
} // namespace wisp
