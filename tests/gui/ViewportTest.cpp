// The 3D viewport, checked on its pixels: the real widget on a real GL context (Mesa llvmpipe under
// Xvfb in CI), the default head, and hand-made strands at known places, located in the image by
// projecting them with the viewport's own camera.
#include "widgets/Viewport.h"
#include "GuiTestSupport.h"
#include "sim/geometry/Body.h"
#include "sim/geometry/DefaultHead.h"
#include "sim/geometry/MeshBvh.h"
#include "sim/params/Parameters.h"
#include "sim/solver/Frame.h"
#include "sim/solver/HairSimulation.h"
#include "widgets/GuideGeometry.h"
#include "widgets/HairDetail.h"
#include "widgets/HairStripLayout.h"
#include "widgets/OrbitCamera.h"
#include "widgets/ViewportOverlay.h"
#include "widgets/ViewportWindow.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QGuiApplication>
#include <QImage>
#include <QLabel>
#include <QMainWindow>
#include <QMouseEvent>
#include <QTest>
#include <QTimer>
#include <QWheelEvent>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <optional>

using namespace wisp;

namespace {

const DefaultHead& defaultHead()
{
    static const DefaultHead head = makeDefaultHead();
    return head;
}

// --- Pixel predicates (sRGB, as grabbed) ----------------------------------------------------------

bool isSkin(QColor c)
{
    return c.red() > 100 && c.red() > c.green() + 12 && c.green() >= c.blue() && c.red() - c.blue() > 35;
}
bool isGreenHair(QColor c)
{
    return c.green() > c.red() + 40 && c.green() > c.blue() + 40;
}
bool isWindBlue(QColor c)
{
    return c.blue() > c.red() + 40 && c.blue() > 90;
}
bool isNearWhite(QColor c)
{
    return c.red() > 225 && c.green() > 225 && c.blue() > 225;
}
bool isEraseRed(QColor c)
{
    return c.red() > 200 && c.green() < 150 && c.blue() < 150;
}
// The growth overlay's tint: orange to magenta, far from skin (whose green is above its blue and
// close to its red).
bool isGrowthTint(QColor c)
{
    return c.red() > 120 && c.red() > c.green() + 90;
}
bool isRed(QColor c)
{
    return c.red() > 90 && c.red() > c.green() + 60 && c.red() > c.blue() + 60;
}
bool isBlue(QColor c)
{
    return c.blue() > 90 && c.blue() > c.red() + 60 && c.blue() > c.green() + 60;
}
bool near(QColor a, QColor b, int tolerance)
{
    return std::abs(a.red() - b.red()) <= tolerance && std::abs(a.green() - b.green()) <= tolerance
        && std::abs(a.blue() - b.blue()) <= tolerance;
}

int countPixels(const QImage& image, const std::function<bool(QColor)>& predicate, QRect area = {})
{
    if (area.isNull())
        area = image.rect();
    area &= image.rect();
    int count = 0;
    for (int y = area.top(); y <= area.bottom(); ++y)
        for (int x = area.left(); x <= area.right(); ++x)
            count += predicate(image.pixelColor(x, y)) ? 1 : 0;
    return count;
}

QRect around(glm::vec2 p, int radius)
{
    return { static_cast<int>(std::lround(p.x)) - radius, static_cast<int>(std::lround(p.y)) - radius, 2 * radius + 1,
        2 * radius + 1 };
}

// How wide a strand's root is on screen, device pixels, at a world point (the style's width).
struct RenderViewProbe {
    float rootPixels = 0.0f;
};
RenderViewProbe probeWidth(const Viewport& viewport, const glm::vec3& point)
{
    const float depth = glm::length(viewport.camera().eye() - point);
    const float metresPerPixel = 2.0f * depth * std::tan(0.5f * glm::radians(viewport.camera().fovYDegrees()))
        / static_cast<float>(viewport.height());
    return { viewport.hairStyle().rootWidthMetres() / metresPerPixel };
}

// Below the HUD line, whose fps figure changes from paint to paint.
int differingPixels(const QImage& a, const QImage& b)
{
    int count = 0;
    for (int y = 40; y < std::min(a.height(), b.height()); ++y)
        for (int x = 0; x < std::min(a.width(), b.width()); ++x)
            count += near(a.pixelColor(x, y), b.pixelColor(x, y), 8) ? 0 : 1;
    return count;
}

// --- Hand-made hair ---------------------------------------------------------------------------------

// A straight lock hanging beside the head (on its +X side, which the start-up view looks at):
// `strands` strands on a disc of radius 4 mm, each `points` points from `top` down `length` metres.
glm::vec3 lockTop(const Aabb& head)
{
    return { head.max.x + 0.05f, head.center().y + 0.10f, head.center().z + 0.02f };
}
constexpr float kLockLength = 0.20f;

void addLock(HairCurves& curves, const glm::vec3& top, int strands, int points, float length)
{
    for (int s = 0; s < strands; ++s) {
        // Golden-angle spiral: even cover of the disc.
        const float r = 0.004f * std::sqrt((s + 0.5f) / strands);
        const float a = 2.39996f * static_cast<float>(s);
        const glm::vec3 root = top + glm::vec3(r * std::cos(a), 0.0f, r * std::sin(a));
        const std::size_t i = curves.addStrand(static_cast<std::uint32_t>(points));
        auto out = curves.strandForWrite(i);
        for (int k = 0; k < points; ++k)
            out[k] = root - glm::vec3(0.0f, length * static_cast<float>(k) / static_cast<float>(points - 1), 0.0f);
    }
}

std::shared_ptr<Frame> lockFrame(const Aabb& head, int strands = 120)
{
    auto frame = std::make_shared<Frame>();
    addLock(frame->strands, lockTop(head), strands, 16, kLockLength);
    frame->simulatedStrands = frame->strands.strandCount();
    frame->simulatedParticles = frame->strands.pointCount();
    frame->stepMilliseconds = 0.123;
    return frame;
}

// About `strands` strands of `points` points rooted over the top and back of the head, hanging
// with some sway: the size of the editor's default scene, for timing.
std::shared_ptr<Frame> scalpFrame(const Aabb& head, int strands, int points, float phase)
{
    auto frame = std::make_shared<Frame>();
    const glm::vec3 c{ head.center().x, head.max.y - 0.3f * head.size().y, head.center().z };
    const float radius = 0.5f * std::max(head.size().x, head.size().z) + 0.005f;
    for (int s = 0; s < strands; ++s) {
        // Fibonacci sphere, upper cap only.
        const float y = 1.0f - 0.9f * (s + 0.5f) / strands;
        const float ring = std::sqrt(std::max(0.0f, 1.0f - y * y));
        const float a = 2.39996f * static_cast<float>(s);
        const glm::vec3 n{ ring * std::cos(a), y, ring * std::sin(a) };
        const std::size_t i = frame->strands.addStrand(static_cast<std::uint32_t>(points));
        auto out = frame->strands.strandForWrite(i);
        glm::vec3 p = c + n * radius;
        glm::vec3 dir = glm::normalize(n + glm::vec3(0.0f, 0.3f, 0.0f));
        for (int k = 0; k < points; ++k) {
            out[k] = p;
            dir = glm::normalize(dir + glm::vec3(0.02f * std::sin(phase + 0.1f * s), -0.25f, 0.0f));
            p += dir * 0.02f;
        }
    }
    frame->simulatedStrands = frame->strands.strandCount();
    frame->simulatedParticles = frame->strands.pointCount();
    return frame;
}

void sendMouse(QWidget* w, QEvent::Type type, QPointF pos, Qt::MouseButton button, Qt::MouseButtons buttons,
    Qt::KeyboardModifiers modifiers)
{
    QMouseEvent event(type, pos, w->mapToGlobal(pos), button, buttons, modifiers);
    QApplication::sendEvent(w, &event);
}

void drag(QWidget* w, Qt::MouseButton button, Qt::KeyboardModifiers modifiers, QPointF from, QPointF to)
{
    sendMouse(w, QEvent::MouseButtonPress, from, button, button, modifiers);
    for (int i = 1; i <= 4; ++i)
        sendMouse(w, QEvent::MouseMove, from + (to - from) * (i / 4.0), Qt::NoButton, button, modifiers);
    sendMouse(w, QEvent::MouseButtonRelease, to, button, Qt::NoButton, modifiers);
}

void wheel(QWidget* w, int eighthsOfDegree)
{
    const QPointF pos(w->width() / 2.0, w->height() / 2.0);
    QWheelEvent event(pos, w->mapToGlobal(pos), QPoint(), QPoint(0, eighthsOfDegree), Qt::NoButton, Qt::NoModifier,
        Qt::NoScrollPhase, false);
    QApplication::sendEvent(w, &event);
}

class ViewportTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        viewport = std::make_unique<Viewport>();
        viewport->resize(640, 480);
        viewport->setHead(defaultHead().mesh);
        viewport->setHairColours(QColor(40, 235, 40), QColor(40, 235, 40));
        viewport->show();
        ASSERT_TRUE(QTest::qWaitForWindowExposed(viewport.get()));
        ASSERT_TRUE(viewport->glStatus().isEmpty()) << viewport->glStatus().toStdString();
        head = viewport->headBounds();
    }
    QImage grab() { return viewport->grabFramebuffer().convertToFormat(QImage::Format_RGB32); }
    // Skin anywhere but under the HUD line (top) and the axis gizmo (bottom left, its red X).
    int skinPixels(const QImage& image)
    {
        return countPixels(image, isSkin, QRect(0, 40, image.width(), image.height() - 40))
            - countPixels(image, isSkin, QRect(0, image.height() - 100, 100, 100));
    }

    std::unique_ptr<Viewport> viewport;
    Aabb head;
};

const MeshBvh& defaultHeadBvh()
{
    static const MeshBvh bvh(defaultHead().mesh);
    return bvh;
}

// The first thing on the head under a widget position, if any.
std::optional<MeshBvh::RayHit> headUnder(const Viewport& viewport, glm::vec2 pixel)
{
    const ViewRay ray = viewport.rayAt(QPointF(pixel.x, pixel.y));
    return defaultHeadBvh().raycast(ray.origin, ray.direction, 100.0f);
}

// The head vertex, among those `wanted` picks, that faces the camera most squarely and that the
// camera sees (nothing of the head in front of it), away from the HUD and the gizmo.
std::optional<std::size_t> visibleFacingVertex(const Viewport& viewport, const std::function<bool(std::size_t)>& wanted)
{
    const TriangleMesh& mesh = defaultHead().mesh;
    static const std::vector<glm::vec3> normals = vertexNormals(mesh);
    std::vector<std::pair<float, std::size_t>> candidates;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        if (!wanted(i))
            continue;
        const glm::vec3 toEye = glm::normalize(viewport.camera().eye() - mesh.positions[i]);
        candidates.emplace_back(glm::dot(normals[i], toEye), i);
    }
    std::sort(candidates.begin(), candidates.end(), std::greater<>());
    for (std::size_t k = 0; k < std::min<std::size_t>(candidates.size(), 200); ++k) {
        const std::size_t i = candidates[k].second;
        const glm::vec2 pixel = viewport.project(mesh.positions[i]);
        if (pixel.y < 50.0f || (pixel.x < 110.0f && pixel.y > viewport.height() - 110.0f))
            continue;
        const auto hit = headUnder(viewport, pixel);
        if (hit && glm::length(hit->point - mesh.positions[i]) < 1e-3f)
            return i;
    }
    return std::nullopt;
}

// Whether a point is well clear (5 mm) of the brush's ring and of its mirror's: a probe of the
// skin there sees no part of a ring, anti-aliased edges included.
bool clearOfTheRings(const BrushCursor& cursor, const glm::vec3& point)
{
    // No point of a circle is nearer than the difference of the distance to its centre and its radius.
    const auto clear
        = [&](const glm::vec3& centre) { return std::abs(glm::length(point - centre) - cursor.radiusMetres) > 0.005f; };
    return clear(cursor.centre) && (!cursor.mirrored || clear(cursor.mirrorCentre));
}

// Points on the brush's circle (as drawn: lifted off the surface), at `count` even angles.
std::vector<glm::vec3> ringPoints(const BrushCursor& cursor, int count)
{
    const glm::vec3 n = glm::normalize(cursor.normal);
    const glm::vec3 u = glm::normalize(glm::cross(n, std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
    const glm::vec3 v = glm::cross(n, u);
    std::vector<glm::vec3> points;
    for (int k = 0; k < count; ++k) {
        const float a = glm::two_pi<float>() * static_cast<float>(k) / static_cast<float>(count);
        points.push_back(
            cursor.centre + n * kBrushRingLiftMetres + cursor.radiusMetres * (std::cos(a) * u + std::sin(a) * v));
    }
    return points;
}

// A brush high on the forehead (where the head is convex, so its flat ring is nowhere under the
// skin), under the widget position above the head's centre.
BrushCursor foreheadBrush(const Viewport& viewport, const Aabb& head)
{
    const glm::vec2 pixel = viewport.project(head.center() + glm::vec3(0.0f, 0.40f * head.size().y, 0.0f));
    const auto hit = headUnder(viewport, pixel);
    BrushCursor cursor;
    if (!hit)
        return cursor;
    cursor.centre = hit->point;
    cursor.normal = faceNormal(defaultHead().mesh, hit->surface.triangle);
    cursor.radiusMetres = 0.02f;
    return cursor;
}

// Rows across the head's silhouette on the left of the view, where nothing but background lies
// beyond it: how many have a pixel just outside the skin that is not plain background, i.e. a
// blend of skin and background, as anti-aliased edges have.
int blendedSilhouetteRows(const QImage& image, const Viewport& viewport, const Aabb& head, int* rows = nullptr)
{
    const glm::vec3 up(0.0f, 0.25f * head.size().y, 0.0f);
    const int top = static_cast<int>(viewport.project(head.center() + up).y);
    const int bottom = static_cast<int>(viewport.project(head.center() - up).y);
    int blended = 0;
    int scanned = 0;
    for (int y = std::max(top, 0); y < std::min(bottom, image.height()); ++y) {
        int x = 0;
        while (x < image.width() && !isSkin(image.pixelColor(x, y)))
            ++x;
        if (x <= 0 || x >= image.width())
            continue;
        ++scanned;
        const QColor background = Viewport::backgroundColour((y + 0.5) / image.height());
        blended += near(image.pixelColor(x - 1, y), background, 6) ? 0 : 1;
    }
    if (rows)
        *rows = scanned;
    return blended;
}

// The native child window a viewport draws into (it is no QObject child of the widget).
ViewportWindow* nativeWindowOf(Viewport& viewport)
{
    for (QWindow* window : QGuiApplication::allWindows())
        if (auto* native = qobject_cast<ViewportWindow*>(window); native && native->inputTarget() == &viewport)
            return native;
    return nullptr;
}

void saveScreenshot(const QImage& image, const char* name)
{
    const QByteArray directory = qgetenv("WISP_SCREENSHOT_DIR");
    if (!directory.isEmpty())
        image.save(QString::fromLocal8Bit(directory) + QLatin1Char('/') + QLatin1String(name));
}

// --- Pure parts -------------------------------------------------------------------------------------

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

// --- The widget ---------------------------------------------------------------------------------------

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
    QWidget window;
    window.resize(640, 480);
    viewport->setParent(&window);
    viewport->move(0, 0);
    window.show();
    viewport->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
    const QImage moved = grab();
    EXPECT_EQ(countPixels(moved, isSkin, around(viewport->project(head.center()), 2)), 25);
    const glm::vec2 lock = viewport->project(lockTop(head) - glm::vec3(0.0f, 0.5f * kLockLength, 0.0f));
    EXPECT_GE(countPixels(moved, isGreenHair, around(lock, 2)), 15);
    viewport->setParent(nullptr);

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
    QWidget window;
    window.resize(640, 480);
    viewport->setParent(&window);
    viewport->move(0, 0);
    window.show();
    viewport->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
    const QImage moved = grab();
    EXPECT_EQ(countPixels(moved, isGrowthTint, around(viewport->project(mesh.positions[*scalp]), 1)), 9);
    int onRing = 0;
    for (const glm::vec3& p : ringPoints(cursor, 24))
        onRing += countPixels(moved, isNearWhite, around(viewport->project(p), 1)) >= 2 ? 1 : 0;
    EXPECT_GE(onRing, 23);
    const glm::vec2 lock = viewport->project(lockTop(head) - glm::vec3(0.0f, 0.5f * kLockLength, 0.0f));
    EXPECT_GE(countPixels(moved, isRed, around(lock, 2)), 15);
    viewport->setParent(nullptr);
}

// What a run of paints did, counted: paints and the strands they drew (as a share of all of them,
// summed over the paints). The seconds are only printed, never asserted (machines are shared).
struct PaintRun {
    int paints = 0;
    double drawnFractionSum = 0.0;
    int fullPaints = 0; // paints that drew every strand
    double seconds = 0.0;
    double perSecond() const { return seconds > 0.0 ? paints / seconds : 0.0; }
    double meanDrawnFraction() const { return paints > 0 ? drawnFractionSum / paints : 0.0; }
};

// `paints` paints as the editor drives the viewport: a new frame arrives through the event loop
// whenever the last one was taken, and the widget repaints on its own schedule. Bounded by a hang
// guard (kWaitMs), not by a time window.
PaintRun paintFrames(Viewport& viewport, const std::vector<FramePtr>& frames, int paints)
{
    std::size_t next = 0;
    QTimer feeder;
    feeder.setInterval(0);
    QObject::connect(&feeder, &QTimer::timeout, [&] { viewport.setFrame(frames[next++ % frames.size()]); });
    PaintRun run;
    std::uint64_t seen = viewport.paintCount();
    QElapsedTimer timer;
    timer.start();
    feeder.start();
    while (run.paints < paints && timer.elapsed() < wisp::test::kWaitMs) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
        if (viewport.paintCount() != seen) { // one look per paint or more: the last paint's share
            run.paints += static_cast<int>(viewport.paintCount() - seen);
            seen = viewport.paintCount();
            run.drawnFractionSum += viewport.lastDrawnFraction();
            run.fullPaints += viewport.lastDrawnFraction() == 1.0f ? 1 : 0;
        }
    }
    feeder.stop();
    run.seconds = static_cast<double>(timer.nsecsElapsed()) * 1e-9;
    return run;
}

// A few paints with the passes timed (PassTimes), the mean of each; timing is off again after
// (unless WISP_PASS_TIMES asked for it from the start: then it was on before, and the untimed
// reading below does not apply; it failed the rate tests when run with it set).
// Untimed, every pass reads zero; timed, the hair (every strand, drawn in every paint) takes time.
PassTimes timedPasses(Viewport& viewport, const std::vector<FramePtr>& frames)
{
    const bool timedFromTheStart = qEnvironmentVariableIsSet("WISP_PASS_TIMES");
    if (!timedFromTheStart)
        EXPECT_EQ(viewport.lastPassTimes().totalMs(), 0.0);
    viewport.setPassTiming(true);
    PassTimes sum;
    constexpr int kTimed = 3;
    for (int i = 0; i < kTimed; ++i) {
        viewport.setFrame(frames[static_cast<std::size_t>(i) % frames.size()]);
        viewport.repaint();
        const PassTimes& t = viewport.lastPassTimes();
        EXPECT_GT(t.hairMs, 0.0);
        EXPECT_GT(t.presentMs, 0.0);
        sum.uploadMs += t.uploadMs / kTimed;
        sum.shadowMs += t.shadowMs / kTimed;
        sum.backdropMs += t.backdropMs / kTimed;
        sum.hairMs += t.hairMs / kTimed;
        sum.presentMs += t.presentMs / kTimed;
    }
    viewport.setPassTiming(timedFromTheStart);
    return sum;
}

// The editor's default scene is ~4,600 strands of 16 points, new every frame. Prints the rates
// (llvmpipe in CI) and checks counts: paints keep coming, every strand is drawn without level of
// detail, and the level of detail never draws more than that.
TEST_F(ViewportTest, DrawRateWithTheDefaultSceneSize)
{
    std::vector<FramePtr> frames;
    for (int i = 0; i < 3; ++i)
        frames.push_back(scalpFrame(head, 4600, 16, static_cast<float>(i)));
    viewport->setLevelOfDetail(false);
    viewport->setFrame(frames[0]);
    grab(); // the first paint builds the layout
    constexpr int kPaints = 12;
    const PaintRun full = paintFrames(*viewport, frames, kPaints);
    const double fullMs = viewport->lastPaintMilliseconds();
    ASSERT_GE(full.paints, kPaints);
    EXPECT_EQ(full.meanDrawnFraction(), 1.0);
    EXPECT_EQ(viewport->lastDrawnFraction(), 1.0f);
    const PassTimes passes = timedPasses(*viewport, frames);
    std::printf("[ viewport ] every strand, per pass: %s\n", qPrintable(passes.describe()));

    viewport->setLevelOfDetail(true);
    const PaintRun adaptive = paintFrames(*viewport, frames, kPaints);
    std::printf("[ viewport ] 4600 strands x 16 points, 640x480, %d samples, %s: every strand %.1f fps "
                "(%.1f ms GL), level of detail %.1f fps (%.0f%% strands, %.1f ms GL)\n",
        viewport->samples(), viewport->softwareRenderer() ? "software GL" : "hardware GL", full.perSecond(), fullMs,
        adaptive.perSecond(), 100.0 * viewport->lastDrawnFraction(), viewport->lastPaintMilliseconds());
    RecordProperty("fps_full", static_cast<int>(std::lround(full.perSecond())));
    RecordProperty("fps_level_of_detail", static_cast<int>(std::lround(adaptive.perSecond())));
    ASSERT_GE(adaptive.paints, kPaints);
    EXPECT_GT(adaptive.meanDrawnFraction(), 0.0);
    EXPECT_LE(adaptive.meanDrawnFraction(), full.meanDrawnFraction()); // never more work than everything
    EXPECT_EQ(adaptive.fullPaints < adaptive.paints, adaptive.meanDrawnFraction() < 1.0);

    if (viewport->lastPaintWasPreview()) {
        // Once frames stop coming, one full-detail paint follows on its own (a bounded wait).
        EXPECT_TRUE(viewport->hudText().contains(QStringLiteral("preview")));
        const std::uint64_t paints = viewport->paintCount();
        EXPECT_TRUE(wisp::test::waitUntil([&] { return !viewport->lastPaintWasPreview(); }));
        EXPECT_GT(viewport->paintCount(), paints);
        EXPECT_EQ(viewport->lastDrawnFraction(), 1.0f);
    }
}

// --- Shadows ---------------------------------------------------------------------------------------

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

TEST_F(ViewportTest, OrbitingAPausedSceneReusesTheShadowsAndMovingHairRendersThem)
{
    viewport->setFrame(scalpFrame(head, 600, 16, 0.0f));
    grab();
    const std::uint64_t passes = viewport->shadowPassCount();
    EXPECT_GE(passes, 1u);
    for (int k = 0; k < 4; ++k) {
        drag(viewport.get(), Qt::MiddleButton, Qt::NoModifier, { 300, 240 }, { 320, 240 });
        grab();
    }
    EXPECT_EQ(viewport->shadowPassCount(), passes); // the key light stays with the head
    viewport->setFrame(scalpFrame(head, 600, 16, 1.0f));
    grab();
    EXPECT_EQ(viewport->shadowPassCount(), passes + 1);
    // A light that follows the camera renders them again as the camera turns.
    viewport->setLightFollowsCamera(true);
    grab();
    const std::uint64_t following = viewport->shadowPassCount();
    drag(viewport.get(), Qt::MiddleButton, Qt::NoModifier, { 300, 240 }, { 340, 240 });
    grab();
    EXPECT_EQ(viewport->shadowPassCount(), following + 1);
    // Off: none rendered.
    viewport->setShadowsEnabled(false);
    viewport->setFrame(scalpFrame(head, 600, 16, 2.0f));
    grab();
    EXPECT_EQ(viewport->shadowPassCount(), following + 1);
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

// --- The native window --------------------------------------------------------------------------------

TEST_F(ViewportTest, InputToItsNativeWindowReachesTheWidgetAndItsEventFilters)
{
    // What the widget and an event filter on it (as the paint tool installs) see of events that
    // reach the child window the frames are drawn into.
    struct Recorder : QObject {
        std::vector<QEvent::Type> seen;
        bool eventFilter(QObject*, QEvent* event) override
        {
            switch (event->type()) {
            case QEvent::MouseButtonPress:
            case QEvent::MouseButtonRelease:
            case QEvent::MouseMove:
            case QEvent::Wheel:
            case QEvent::KeyPress:
            case QEvent::Enter:
            case QEvent::Leave:
                seen.push_back(event->type());
                break;
            default:
                break;
            }
            return false;
        }
        int count(QEvent::Type type) const { return static_cast<int>(std::count(seen.begin(), seen.end(), type)); }
    } recorder;
    viewport->installEventFilter(&recorder);
    ViewportWindow* window = nativeWindowOf(*viewport);
    ASSERT_NE(window, nullptr);
    ASSERT_TRUE(QTest::qWaitForWindowExposed(window));
    EXPECT_EQ(window->size(), viewport->size());

    // Alt + left drag orbits, in the widget's own handlers.
    const float yaw = viewport->camera().yaw();
    QTest::mousePress(window, Qt::LeftButton, Qt::AltModifier, QPoint(300, 240));
    QTest::mouseMove(window, QPoint(340, 240));
    QTest::mouseRelease(window, Qt::LeftButton, Qt::AltModifier, QPoint(340, 240));
    EXPECT_NE(viewport->camera().yaw(), yaw);
    EXPECT_GE(recorder.count(QEvent::MouseButtonPress), 1);
    EXPECT_GE(recorder.count(QEvent::MouseButtonRelease), 1);

    // Moves without a button reach the widget only while it tracks the mouse, as for widgets.
    recorder.seen.clear();
    QTest::mouseMove(window, QPoint(200, 200));
    EXPECT_EQ(recorder.count(QEvent::MouseMove), 0);
    viewport->setMouseTracking(true);
    QTest::mouseMove(window, QPoint(210, 200));
    EXPECT_EQ(recorder.count(QEvent::MouseMove), 1);

    // The wheel zooms; F frames the head.
    const float distance = viewport->camera().distance();
    QWheelEvent wheelEvent(QPointF(320, 240), window->mapToGlobal(QPointF(320, 240)), QPoint(), QPoint(0, 240),
        Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QCoreApplication::sendEvent(window, &wheelEvent);
    EXPECT_LT(viewport->camera().distance(), distance);
    EXPECT_EQ(recorder.count(QEvent::Wheel), 1);
    QTest::keyClick(window, Qt::Key_F);
    EXPECT_EQ(recorder.count(QEvent::KeyPress), 1);
    EXPECT_NEAR(viewport->camera().distance(), distance, 1e-4f);

    // Leaving the window is leaving the widget (the paint tool hides its ring then).
    QEvent leave(QEvent::Leave);
    QCoreApplication::sendEvent(window, &leave);
    EXPECT_EQ(recorder.count(QEvent::Leave), 1);

    // The widget's cursor is the window's.
    viewport->setCursor(Qt::CrossCursor);
    EXPECT_EQ(window->cursor().shape(), Qt::CrossCursor);
    viewport->removeEventFilter(&recorder);
}

TEST_F(ViewportTest, WindowShortcutsWorkWhileTheViewHasTheFocus)
{
    // The editor's Space (play) is a window shortcut: it must still fire once a click in the view
    // has given the focus to the view's native window.
    QWidget window;
    window.resize(640, 480);
    viewport->setParent(&window);
    viewport->move(0, 0);
    QAction play(&window);
    play.setShortcut(QKeySequence(Qt::Key_Space));
    window.addAction(&play);
    int triggered = 0;
    QObject::connect(&play, &QAction::triggered, [&] { ++triggered; });
    window.show();
    viewport->show();
    window.activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(&window));
    ViewportWindow* native = nativeWindowOf(*viewport);
    ASSERT_NE(native, nullptr);
    native->requestActivate();
    ASSERT_TRUE(QTest::qWaitFor([&] { return QGuiApplication::focusWindow() == native; }));
    QTest::keyClick(native, Qt::Key_Space);
    EXPECT_EQ(triggered, 1);
    // Keys no shortcut takes go to the view.
    QTest::keyClick(native, Qt::Key_F);
    EXPECT_NEAR(viewport->project(head.center()).x, 320.0f, 1.0f);
    viewport->setParent(nullptr);
}

TEST_F(ViewportTest, UpdateAndRepaintDrawFrames)
{
    const std::uint64_t before = viewport->paintCount();
    viewport->repaint();
    EXPECT_GT(viewport->paintCount(), before);
    const std::uint64_t repainted = viewport->paintCount();
    viewport->update();
    EXPECT_TRUE(QTest::qWaitFor([&] { return viewport->paintCount() > repainted; }, 2000));
}

TEST_F(ViewportTest, FramesFromTheBackdropMatchFramesDrawnWhole)
{
    // Once the camera holds still, frames start from a copy of the background, head and guides
    // drawn before: the picture must be the same as one drawn whole (right after the camera moved).
    const glm::vec3 wind{ -8.0f, 0.0f, 0.0f }; // frames carry the wind the arrow shows
    auto frame = scalpFrame(head, 600, 16, 0.0f);
    frame->wind = wind;
    auto moved = scalpFrame(head, 600, 16, 1.0f);
    moved->wind = wind;
    viewport->setFrame(frame);
    viewport->setGrowthOverlay(defaultHead().growthWeights);
    BrushCursor cursor = foreheadBrush(*viewport, head);
    cursor.mirrored = true;
    cursor.mirrorCentre = cursor.centre * glm::vec3(-1.0f, 1.0f, 1.0f);
    cursor.mirrorNormal = cursor.normal * glm::vec3(-1.0f, 1.0f, 1.0f);
    viewport->setBrushCursor(cursor);
    for (const QPointF to : { QPointF(330, 240), QPointF(250, 200) }) {
        drag(viewport.get(), Qt::MiddleButton, Qt::NoModifier, { 300, 240 }, to);
        const QImage whole = grab();
        const QImage fromBackdrop = grab();
        EXPECT_EQ(differingPixels(whole, fromBackdrop), 0);
        viewport->setFrame(moved); // the hair moves, the backdrop stays
        EXPECT_GT(differingPixels(fromBackdrop, grab()), 0);
        viewport->setFrame(frame);
        EXPECT_EQ(differingPixels(whole, grab()), 0);
    }
}

TEST_F(ViewportTest, EdgesStayAntiAliasedFrameAfterFrame)
{
    // The head's silhouette against the background, in the third frame drawn (a leak of GL state
    // from one frame into the next once turned multisampling off after the first), with the
    // default 4x MSAA and without it.
    if (qEnvironmentVariableIsSet("WISP_VIEWPORT_SAMPLES"))
        GTEST_SKIP() << "WISP_VIEWPORT_SAMPLES chooses the samples of this run";
    viewport->setFrame(nullptr);
    grab();
    grab();
    int rows = 0;
    const int smooth = blendedSilhouetteRows(grab(), *viewport, head, &rows);
    ASSERT_GT(rows, 50);
    EXPECT_GT(viewport->samples(), 1);

    qputenv("WISP_VIEWPORT_SAMPLES", "0");
    Viewport aliased;
    qunsetenv("WISP_VIEWPORT_SAMPLES");
    aliased.resize(640, 480);
    aliased.setHead(defaultHead().mesh);
    aliased.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&aliased));
    aliased.grabFramebuffer();
    const int hard = blendedSilhouetteRows(
        aliased.grabFramebuffer().convertToFormat(QImage::Format_RGB32), aliased, aliased.headBounds());
    EXPECT_EQ(aliased.samples(), 0);
    std::printf("[ viewport ] silhouette rows with a blended pixel: %d of %d with %d samples, %d without\n", smooth,
        rows, viewport->samples(), hard);
    EXPECT_GT(smooth, rows / 2);
    EXPECT_LT(hard, rows / 5);
}

// The editor's viewport sits between docks in a 1400x900 window. Drawing into a native child
// window, its frames cost what they cost on their own: nothing of the rest of the window is drawn
// again. Prints the rates (software GL in CI) beside the standalone view's.
TEST_F(ViewportTest, DrawRateBetweenDocksInTheEditorsWindowSize)
{
    std::vector<FramePtr> frames;
    for (int i = 0; i < 3; ++i)
        frames.push_back(scalpFrame(head, 4600, 16, static_cast<float>(i)));
    QMainWindow window;
    window.resize(1400, 900);
    for (Qt::DockWidgetArea area : { Qt::LeftDockWidgetArea, Qt::RightDockWidgetArea }) {
        auto* dock = new QDockWidget(QStringLiteral("Panel"), &window);
        dock->setWidget(new QLabel(QStringLiteral("A panel's worth of widgets"), dock));
        dock->setMinimumWidth(330);
        window.addDockWidget(area, dock);
    }
    window.setCentralWidget(viewport.get());
    window.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
    viewport->setFrame(frames[0]);
    grab(); // the first paint builds the layout
    const PaintRun run = paintFrames(*viewport, frames, 12);
    const double rate = run.perSecond();
    std::printf("[ viewport ] between docks, per pass: %s\n", qPrintable(timedPasses(*viewport, frames).describe()));
    std::printf("[ viewport ] 4600 strands x 16 points, %dx%d between docks of a %dx%d window, %s: level of detail "
                "%.1f fps (%.0f%% strands, %.1f ms GL)\n",
        viewport->width(), viewport->height(), window.width(), window.height(),
        viewport->softwareRenderer() ? "software GL" : "hardware GL", rate, 100.0 * viewport->lastDrawnFraction(),
        viewport->lastPaintMilliseconds());
    RecordProperty("fps_editor_window", static_cast<int>(std::lround(rate)));
    EXPECT_GE(run.paints, 12); // frames keep being drawn between the docks
    EXPECT_GT(run.meanDrawnFraction(), 0.0);
    window.takeCentralWidget();
    viewport->setParent(nullptr);
}

} // namespace
