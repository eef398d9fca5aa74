// Scalp painting as an artist does it: the real window, the brush driven by mouse and key events
// on the viewport, and the published frames' roots checked against where the stroke went.
#include "GuiTestSupport.h"
#include "app/editor/BrushPanel.h"
#include "app/editor/Document.h"
#include "app/editor/MainWindow.h"
#include "app/editor/PaintTool.h"
#include "app/editor/SimulationHost.h"
#include "app/editor/WispPanel.h"
#include "sim/geometry/MeshBvh.h"
#include "sim/style/StrandPicking.h"
#include "widgets/ParameterPanel.h"
#include "widgets/Viewport.h"

#include <QAction>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTest>
#include <QUndoStack>

#include <glm/trigonometric.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

using namespace wisp;

namespace {

using Root = std::tuple<float, float, float>;

std::set<Root> rootsOf(const FramePtr& frame)
{
    std::set<Root> roots;
    for (std::size_t s = 0; s < frame->strands.strandCount(); ++s) {
        const glm::vec3 p = frame->strands.strand(s).front();
        roots.insert({ p.x, p.y, p.z });
    }
    return roots;
}

glm::vec3 asVec(const Root& r)
{
    return { std::get<0>(r), std::get<1>(r), std::get<2>(r) };
}

class PaintingTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        window = wisp::test::openLightPausedEditor();
        ASSERT_FALSE(HasFailure()) << "the editor did not open paused on a light groom";
        bvh = std::make_unique<MeshBvh>(window->document()->head());
    }

    // Waits until the host has taken every edit: no regroom for a while.
    void settle() { wisp::test::waitUntilRegroomsStop(*window->simulation(), 600 * WISP_SLOW_BUILD_FACTOR); }
    FramePtr frame() const { return window->simulation()->latestFrame(); }

    // A point on the right cheek (no hair there by default), seen from the side, and where it shows.
    glm::vec3 cheek(float dy) const
    {
        const Aabb box = boundsOf(window->document()->head());
        return bvh->closestPoint({ box.max.x + 0.05f, box.center().y - 0.01f + dy, box.center().z + 0.02f }).point;
    }
    void lookFromTheRight()
    {
        OrbitCamera& camera = window->viewport()->camera();
        camera.setOrientation(glm::radians(90.0f), 0.0f);
        window->viewport()->update();
        QTest::qWait(50);
    }
    QPoint screenOf(const glm::vec3& p) const
    {
        const glm::vec2 s = window->viewport()->project(p);
        return { static_cast<int>(std::lround(s.x)), static_cast<int>(std::lround(s.y)) };
    }
    // Drags the brush through `points` (world, on the head) with the given modifiers; returns the
    // surface points the stroke passed through.
    void stroke(const std::vector<glm::vec3>& points, Qt::KeyboardModifiers modifiers = Qt::NoModifier)
    {
        Viewport* view = window->viewport();
        QTest::mousePress(view, Qt::LeftButton, modifiers, screenOf(points.front()));
        for (std::size_t i = 1; i < points.size(); ++i) {
            const QPoint at = screenOf(points[i]);
            QMouseEvent move(QEvent::MouseMove, at, view->mapToGlobal(at), Qt::NoButton, Qt::LeftButton, modifiers);
            QApplication::sendEvent(view, &move);
            QTest::qWait(5);
        }
        QTest::mouseRelease(view, Qt::LeftButton, modifiers, screenOf(points.back()));
        settle();
    }

    std::unique_ptr<MainWindow> window;
    std::unique_ptr<MeshBvh> bvh;
};

} // namespace

TEST_F(PaintingTest, AStrokeAddsRootsOnlyNearItAndItsMirrorAndUndoRedoAreExact)
{
    lookFromTheRight();
    QTest::keyClick(window->viewport(), Qt::Key_B); // the paint tool, as an artist switches to it
    ASSERT_TRUE(window->paintTool()->isActive());
    const float radius = window->paintTool()->settings().radiusMetres;
    ASSERT_TRUE(window->paintTool()->settings().mirrorX) << "symmetry is on by default";

    const std::set<Root> before = rootsOf(frame());
    const RegionWeights weightsBefore = window->document()->region(0).weights;
    const std::vector<glm::vec3> line{ cheek(-0.015f), cheek(0.0f), cheek(0.015f) };
    stroke(line);
    ASSERT_EQ(window->document()->undoStack()->count(), 1) << "one stroke, one undo step";
    const std::set<Root> after = rootsOf(frame());
    ASSERT_GT(after.size(), before.size() + 5);

    // Every new root lies near the stroke or its mirror, and the mirror side got roots too.
    const float plane = window->paintTool()->mirrorPlaneX();
    std::vector<glm::vec3> mirrored;
    for (const glm::vec3& p : line)
        mirrored.push_back({ 2.0f * plane - p.x, p.y, p.z });
    int nearStroke = 0, nearMirror = 0;
    for (const Root& r : after) {
        if (before.count(r))
            continue;
        const glm::vec3 p = asVec(r);
        const float toStroke = distanceToPolyline(p, line), toMirror = distanceToPolyline(p, mirrored);
        EXPECT_LT(std::min(toStroke, toMirror), radius + 0.005f) << "a root grew away from the brush";
        ++(toStroke < toMirror ? nearStroke : nearMirror);
    }
    EXPECT_GT(nearStroke, 2);
    EXPECT_GT(nearMirror, 2);
    // Nothing elsewhere moved: every root from before is still there.
    EXPECT_TRUE(std::includes(after.begin(), after.end(), before.begin(), before.end()));

    window->document()->undoStack()->undo();
    settle();
    EXPECT_EQ(window->document()->region(0).weights, weightsBefore);
    EXPECT_EQ(rootsOf(frame()), before);
    window->document()->undoStack()->redo();
    settle();
    EXPECT_EQ(rootsOf(frame()), after);

    // Ctrl erases what the stroke grew.
    stroke(line, Qt::ControlModifier);
    const std::set<Root> erased = rootsOf(frame());
    EXPECT_LT(erased.size(), after.size() - 5);
    // Erasing never adds roots. (A member's root is rebuilt from its key hair's, so when erasing
    // picks a new key for a wisp its members' roots may differ in the last bits.)
    for (const Root& r : erased) {
        const bool existed = std::any_of(
            after.begin(), after.end(), [&](const Root& a) { return glm::distance(asVec(a), asVec(r)) < 1e-5f; });
        EXPECT_TRUE(existed) << "erasing added a root";
    }
}

TEST_F(PaintingTest, BracketKeysResizeTheBrushAndTheRingFollowsTheCursor)
{
    lookFromTheRight();
    window->paintAction()->trigger();
    const float radius = window->paintTool()->settings().radiusMetres;
    QTest::keyClick(window->viewport(), Qt::Key_BracketRight);
    EXPECT_GT(window->paintTool()->settings().radiusMetres, radius * 1.1f);
    QTest::keyClick(window->viewport(), Qt::Key_BracketLeft);
    QTest::keyClick(window->viewport(), Qt::Key_BracketLeft);
    EXPECT_LT(window->paintTool()->settings().radiusMetres, radius * 0.9f);
    EXPECT_NEAR(window->brushPanel()->radiusBox()->value(), window->paintTool()->settings().radiusMetres * 100.0, 0.01);

    // A hover (no button): sent to the viewport as Qt delivers it (QTest::mouseMove moves the real
    // pointer, which Xvfb does not always report).
    const QPoint at = screenOf(cheek(0.0f));
    QMouseEvent hover(
        QEvent::MouseMove, at, window->viewport()->mapToGlobal(at), Qt::NoButton, Qt::NoButton, Qt::NoModifier);
    QApplication::sendEvent(window->viewport(), &hover);
    ASSERT_TRUE(window->viewport()->brushCursor().has_value());
    EXPECT_LT(glm::distance(window->viewport()->brushCursor()->centre, cheek(0.0f)), 0.004f);
    EXPECT_TRUE(window->viewport()->brushCursor()->mirrored);
    window->paintAction()->trigger(); // off: no ring
    EXPECT_FALSE(window->viewport()->brushCursor().has_value());
}

TEST_F(PaintingTest, WispSizeOfOneRegionChangesOnlyThatRegionsStrands)
{
    lookFromTheRight();
    Document* doc = window->document();
    doc->addRegion(QStringLiteral("Sideburns"));
    ASSERT_EQ(doc->currentRegion(), 1);
    window->paintAction()->trigger();
    stroke({ cheek(-0.015f), cheek(0.0f), cheek(0.015f) });
    const FramePtr before = frame();
    ASSERT_FALSE(before->lookOfStrand.empty());

    // The wisp panel edits the current region (the new one): type a wisp size as an artist does.
    wisp::test::typeValue(window->wispPanel()->parameterPanel(), Param::WispSize, QStringLiteral("2"));
    settle();
    ASSERT_EQ(doc->region(1).values.getInt(Param::WispSize), 2);
    EXPECT_EQ(doc->region(0).values.getInt(Param::WispSize), 12);
    const FramePtr after = frame();

    auto strandsOf = [](const FramePtr& f, int look) {
        std::map<Root, std::vector<glm::vec3>> out;
        for (std::size_t s = 0; s < f->strands.strandCount(); ++s)
            if (f->lookOfStrand[s] == look) {
                const auto points = f->strands.strand(s);
                out[{ points[0].x, points[0].y, points[0].z }] = { points.begin(), points.end() };
            }
        return out;
    };
    EXPECT_EQ(strandsOf(after, 0), strandsOf(before, 0)) << "the first region's strands must not change";
    EXPECT_NE(strandsOf(after, 1), strandsOf(before, 1));
    EXPECT_EQ(strandsOf(after, 1).size(), strandsOf(before, 1).size()) << "wisp size regroups, it does not add roots";
}
