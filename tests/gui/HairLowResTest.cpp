// The hair at half resolution while the camera or the hair moves (HairLowResTarget): the same
// coverage and colour as at full resolution, hair behind the head kept behind it, and a still view
// drawn whole. The scene is the editor's default groom, draped, in its default view.

#include "SettledViewportTest.h"
#include "ViewportTestSupport.h"

#include "app/editor/Document.h"
#include "app/editor/SettledScene.h"
#include "sim/geometry/Body.h"
#include "widgets/Viewport.h"

#include <QImage>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace wisp {
namespace {

class HairLowResTest : public test::SettledViewportTest {
protected:
    static int difference(QRgb a, QRgb b)
    {
        return std::abs(qRed(a) - qRed(b)) + std::abs(qGreen(a) - qGreen(b)) + std::abs(qBlue(a) - qBlue(b));
    }
    static constexpr QSize kSize{ 585, 710 };
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

} // namespace
} // namespace wisp
