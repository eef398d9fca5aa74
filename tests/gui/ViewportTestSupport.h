#pragma once
// What the viewport's GUI tests share (ViewportTest.cpp, ViewportPartsTest.cpp,
// ViewportBrushOverlayTest.cpp, ViewportDrawRateTest.cpp, ViewportShadowTest.cpp,
// ViewportWindowTest.cpp): pixel predicates and counts, hand-made hair, mouse input, brush rings on
// the default head, and the ViewportTest fixture (a shown 640x480 Viewport on the default head).

#include "../sim/SimFixtures.h"
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
#include "widgets/Viewport.h"
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
#include <QWidget>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <optional>

namespace wisp::test {

// --- Pixel predicates (sRGB, as grabbed) ----------------------------------------------------------

inline bool isSkin(QColor c)
{
    return c.red() > 100 && c.red() > c.green() + 12 && c.green() >= c.blue() && c.red() - c.blue() > 35;
}
inline bool isGreenHair(QColor c)
{
    return c.green() > c.red() + 40 && c.green() > c.blue() + 40;
}
inline bool isWindBlue(QColor c)
{
    return c.blue() > c.red() + 40 && c.blue() > 90;
}
inline bool isNearWhite(QColor c)
{
    return c.red() > 225 && c.green() > 225 && c.blue() > 225;
}
inline bool isEraseRed(QColor c)
{
    return c.red() > 200 && c.green() < 150 && c.blue() < 150;
}
// The growth overlay's tint: orange to magenta, far from skin (whose green is above its blue and
// close to its red).
inline bool isGrowthTint(QColor c)
{
    return c.red() > 120 && c.red() > c.green() + 90;
}
inline bool isRed(QColor c)
{
    return c.red() > 90 && c.red() > c.green() + 60 && c.red() > c.blue() + 60;
}
inline bool isBlue(QColor c)
{
    return c.blue() > 90 && c.blue() > c.red() + 60 && c.blue() > c.green() + 60;
}
inline bool near(QColor a, QColor b, int tolerance)
{
    return std::abs(a.red() - b.red()) <= tolerance && std::abs(a.green() - b.green()) <= tolerance
        && std::abs(a.blue() - b.blue()) <= tolerance;
}

inline int countPixels(const QImage& image, const std::function<bool(QColor)>& predicate, QRect area = {})
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

inline QRect around(glm::vec2 p, int radius)
{
    return { static_cast<int>(std::lround(p.x)) - radius, static_cast<int>(std::lround(p.y)) - radius, 2 * radius + 1,
        2 * radius + 1 };
}

// How wide a strand's root is on screen, device pixels, at a world point (the style's width).
struct RenderViewProbe {
    float rootPixels = 0.0f;
};
inline RenderViewProbe probeWidth(const Viewport& viewport, const glm::vec3& point)
{
    const float depth = glm::length(viewport.camera().eye() - point);
    const float metresPerPixel = 2.0f * depth * std::tan(0.5f * glm::radians(viewport.camera().fovYDegrees()))
        / static_cast<float>(viewport.height());
    return { viewport.hairStyle().rootWidthMetres() / metresPerPixel };
}

// Below the HUD line, whose fps figure changes from paint to paint.
inline int differingPixels(const QImage& a, const QImage& b)
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
inline glm::vec3 lockTop(const Aabb& head)
{
    return { head.max.x + 0.05f, head.center().y + 0.10f, head.center().z + 0.02f };
}
inline constexpr float kLockLength = 0.20f;

inline void addLock(HairCurves& curves, const glm::vec3& top, int strands, int points, float length)
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

inline std::shared_ptr<Frame> lockFrame(const Aabb& head, int strands = 120)
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
inline std::shared_ptr<Frame> scalpFrame(const Aabb& head, int strands, int points, float phase)
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

inline void sendMouse(QWidget* w, QEvent::Type type, QPointF pos, Qt::MouseButton button, Qt::MouseButtons buttons,
    Qt::KeyboardModifiers modifiers)
{
    QMouseEvent event(type, pos, w->mapToGlobal(pos), button, buttons, modifiers);
    QApplication::sendEvent(w, &event);
}

inline void drag(QWidget* w, Qt::MouseButton button, Qt::KeyboardModifiers modifiers, QPointF from, QPointF to)
{
    sendMouse(w, QEvent::MouseButtonPress, from, button, button, modifiers);
    for (int i = 1; i <= 4; ++i)
        sendMouse(w, QEvent::MouseMove, from + (to - from) * (i / 4.0), Qt::NoButton, button, modifiers);
    sendMouse(w, QEvent::MouseButtonRelease, to, button, Qt::NoButton, modifiers);
}

inline void wheel(QWidget* w, int eighthsOfDegree)
{
    const QPointF pos(w->width() / 2.0, w->height() / 2.0);
    QWheelEvent event(pos, w->mapToGlobal(pos), QPoint(), QPoint(0, eighthsOfDegree), Qt::NoButton, Qt::NoModifier,
        Qt::NoScrollPhase, false);
    QApplication::sendEvent(w, &event);
}

// The viewport moved into a new window of its own, shown and exposed (check exposed()): a new GL
// context, so everything it draws is uploaded again. Back out of the window (parentless) when this
// goes, before the window does.
class ViewportInNewWindow {
public:
    explicit ViewportInNewWindow(Viewport& viewport)
        : m_viewport(viewport)
    {
        m_window.resize(640, 480);
        viewport.setParent(&m_window);
        viewport.move(0, 0);
        m_window.show();
        viewport.show();
        m_exposed = QTest::qWaitForWindowExposed(&m_window);
    }
    ~ViewportInNewWindow() { m_viewport.setParent(nullptr); }
    ViewportInNewWindow(const ViewportInNewWindow&) = delete;
    ViewportInNewWindow& operator=(const ViewportInNewWindow&) = delete;

    bool exposed() const { return m_exposed; }

private:
    Viewport& m_viewport;
    QWidget m_window;
    bool m_exposed = false;
};

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

inline const MeshBvh& defaultHeadBvh()
{
    static const MeshBvh bvh(defaultHead().mesh);
    return bvh;
}

// The first thing on the head under a widget position, if any.
inline std::optional<MeshBvh::RayHit> headUnder(const Viewport& viewport, glm::vec2 pixel)
{
    const ViewRay ray = viewport.rayAt(QPointF(pixel.x, pixel.y));
    return defaultHeadBvh().raycast(ray.origin, ray.direction, 100.0f);
}

// The head vertex, among those `wanted` picks, that faces the camera most squarely and that the
// camera sees (nothing of the head in front of it), away from the HUD and the gizmo.
inline std::optional<std::size_t> visibleFacingVertex(
    const Viewport& viewport, const std::function<bool(std::size_t)>& wanted)
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
inline bool clearOfTheRings(const BrushCursor& cursor, const glm::vec3& point)
{
    // No point of a circle is nearer than the difference of the distance to its centre and its radius.
    const auto clear
        = [&](const glm::vec3& centre) { return std::abs(glm::length(point - centre) - cursor.radiusMetres) > 0.005f; };
    return clear(cursor.centre) && (!cursor.mirrored || clear(cursor.mirrorCentre));
}

// Points on the brush's circle (as drawn: lifted off the surface), at `count` even angles.
inline std::vector<glm::vec3> ringPoints(const BrushCursor& cursor, int count)
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
inline BrushCursor foreheadBrush(const Viewport& viewport, const Aabb& head)
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
inline int blendedSilhouetteRows(const QImage& image, const Viewport& viewport, const Aabb& head, int* rows = nullptr)
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
inline ViewportWindow* nativeWindowOf(Viewport& viewport)
{
    for (QWindow* window : QGuiApplication::allWindows())
        if (auto* native = qobject_cast<ViewportWindow*>(window); native && native->inputTarget() == &viewport)
            return native;
    return nullptr;
}

inline void saveScreenshot(const QImage& image, const char* name)
{
    const QByteArray directory = qgetenv("WISP_SCREENSHOT_DIR");
    if (!directory.isEmpty())
        image.save(QString::fromLocal8Bit(directory) + QLatin1Char('/') + QLatin1String(name));
}

} // namespace wisp::test
