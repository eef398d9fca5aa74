#pragma once
// What the styling GUI tests share (StylingTest.cpp, StylingDryerTest.cpp, StylingProjectTest.cpp):
// strands by identity, wisp spread, and the StylingTest fixture (the real window on a light groom,
// paused and hanging at rest; strokes and brush shortcuts as an artist gives them).

#include "GuiTestSupport.h"
#include "app/editor/BrushPanel.h"
#include "app/editor/Document.h"
#include "app/editor/FileMenu.h"
#include "app/editor/MainWindow.h"
#include "app/editor/PaintTool.h"
#include "app/editor/PresetBrowser.h"
#include "app/editor/ProjectController.h"
#include "app/editor/SimulationHost.h"
#include "app/editor/StylePanel.h"
#include "app/editor/StyleTool.h"
#include "io/PresetFile.h"
#include "sim/geometry/SignedDistanceField.h"
#include "sim/style/HairDryer.h"
#include "sim/style/StrandPicking.h"
#include "widgets/Viewport.h"

#include <QAction>
#include <QCheckBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QListWidget>
#include <QPainter>
#include <QPushButton>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>

namespace wisp::test {

using Strands = std::map<std::uint64_t, std::vector<glm::vec3>>;

inline Strands byIdentity(const FramePtr& frame, bool rest = false)
{
    Strands out;
    const HairCurves& curves = rest ? frame->groomShape->rest.anySpace() : frame->strands.anySpace();
    for (std::size_t i = 0; i < curves.strandCount(); ++i) {
        const auto s = curves.strand(i);
        out[frame->groomShape->identities[i]] = { s.begin(), s.end() };
    }
    return out;
}

inline std::set<std::uint64_t> keyIdentities(const FramePtr& frame)
{
    std::set<std::uint64_t> keys;
    for (std::uint32_t k : frame->groomShape->keyOfWisp)
        keys.insert(frame->groomShape->identities[k]);
    return keys;
}

// How spread wisp w is: the mean distance of its members' outer halves from its key hair.
inline float wispSpread(const FramePtr& frame, std::uint32_t w)
{
    const GroomShape& g = *frame->groomShape;
    const auto key = frame->strands.strand(g.keyOfWisp[w]);
    double sum = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < g.wispOf.size(); ++i) {
        if (g.wispOf[i] != w || i == g.keyOfWisp[w])
            continue;
        const auto member = frame->strands.strand(i);
        for (std::size_t j = member.size() / 2; j < member.size(); ++j, ++n)
            sum += distanceToPolyline(member[j], key);
    }
    return n == 0 ? 0.0f : static_cast<float>(sum / n);
}

class StylingTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        // A light groom, even lengths, no wind.
        window = wisp::test::openLightPausedEditor(
            [](Document& doc) {
                doc.editRegionParameter(0, Param::LengthVariation, 0.0, false);
                doc.editParameter(Param::WindSpeed, 0.0, false);
                doc.editParameter(Param::Turbulence, 0.0, false);
            },
            kQuietMs);
        ASSERT_FALSE(HasFailure()) << "the editor did not open paused on a light groom";
        runSteps(240); // hanging, at rest
        box = boundsOf(window->document()->head());
    }

    // Waits until the host has taken every edit: no regroom for a while.
    void settle() { wisp::test::waitUntilRegroomsStop(*window->simulation(), kQuietMs); }
    static constexpr int kQuietMs = 800 * WISP_SLOW_BUILD_FACTOR;
    // Runs `action`, which gives the host a new groom (File ▸ New, Open), and waits until a frame
    // of it arrives, then until every edit is taken. The quiet wait alone is not enough there: on a
    // loaded machine the new groom and drape can take longer than kQuietMs, and the frame read
    // after it was still the old groom's (a reopened project compared 882 of its 1,080 styled
    // strands against the New project's). False when no new groom came within the scene guard.
    [[nodiscard]] bool settleNewGroom(const std::function<bool()>& action)
    {
        const std::uint64_t before = frame()->groomVersion;
        if (!action())
            return false;
        if (!wisp::test::waitUntil([&] { return frame()->groomVersion > before; }, wisp::test::kSceneWaitMs))
            return false;
        settle();
        return true;
    }
    // Steps a paused simulation `count` times, as fast as it goes.
    void runSteps(int count)
    {
        SimulationHost* host = window->simulation();
        for (int i = 0; i < count; ++i) {
            const std::uint64_t since = host->publishedFrames();
            host->stepOnce();
            ASSERT_TRUE(wisp::test::waitForFramesSince(*host, since, 1));
        }
    }
    FramePtr frame() const { return window->simulation()->latestFrame(); }
    Document* document() const { return window->document(); }

    // The camera looks along -x (from the head's right) or -z (from the front) at `pivot`, level.
    void look(float yawDegrees, const glm::vec3& pivot, float distance = 0.7f)
    {
        OrbitCamera& camera = window->viewport()->camera();
        camera.setPivot(pivot);
        camera.setOrientation(glm::radians(yawDegrees), 0.0f);
        camera.setDistance(distance);
        window->viewport()->update();
        QTest::qWait(50);
    }
    QPoint screenOf(const glm::vec3& p) const
    {
        const glm::vec2 s = window->viewport()->project(p);
        return { static_cast<int>(std::lround(s.x)), static_cast<int>(std::lround(s.y)) };
    }
    // Presses at the first point, moves through the others (in `steps` even moves between each
    // pair) and releases at the last: real mouse events on the viewport.
    void stroke(const std::vector<glm::vec3>& points, Qt::KeyboardModifiers modifiers = Qt::NoModifier, int steps = 8)
    {
        Viewport* view = window->viewport();
        QTest::mousePress(view, Qt::LeftButton, modifiers, screenOf(points.front()));
        for (std::size_t i = 1; i < points.size(); ++i)
            for (int k = 1; k <= steps; ++k) {
                const QPoint at = screenOf(glm::mix(points[i - 1], points[i], static_cast<float>(k) / steps));
                QMouseEvent move(QEvent::MouseMove, at, view->mapToGlobal(at), Qt::NoButton, Qt::LeftButton, modifiers);
                QApplication::sendEvent(view, &move);
                QTest::qWait(10);
            }
        QTest::mouseRelease(view, Qt::LeftButton, modifiers, screenOf(points.back()));
        settle();
    }
    void pick(Qt::Key shortcut, StyleBrush expected)
    {
        QTest::keyClick(window->viewport(), shortcut);
        ASSERT_EQ(window->styleTool()->brush(), expected);
    }
    void undo()
    {
        QTest::keyClick(window->viewport(), Qt::Key_Z, Qt::ControlModifier);
        settle();
    }
    // The right side of the head at height dy below its centre, just outside it.
    glm::vec3 rightSide(float dy, float dz = 0.0f) const
    {
        return { box.max.x + 0.01f, box.center().y - dy, box.center().z + dz };
    }

    std::unique_ptr<MainWindow> window;
    Aabb box;
};

} // namespace wisp::test
