// Styling on live hair as an artist does it: the real window, each salon brush picked by its
// shortcut and driven by mouse events on the viewport, the published frames measured.
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

using namespace wisp;

namespace {

using Strands = std::map<std::uint64_t, std::vector<glm::vec3>>;

Strands byIdentity(const FramePtr& frame, bool rest = false)
{
    Strands out;
    const HairCurves& curves = rest ? frame->groomShape->rest.anySpace() : frame->strands.anySpace();
    for (std::size_t i = 0; i < curves.strandCount(); ++i) {
        const auto s = curves.strand(i);
        out[frame->groomShape->identities[i]] = { s.begin(), s.end() };
    }
    return out;
}

std::set<std::uint64_t> keyIdentities(const FramePtr& frame)
{
    std::set<std::uint64_t> keys;
    for (std::uint32_t k : frame->groomShape->keyOfWisp)
        keys.insert(frame->groomShape->identities[k]);
    return keys;
}

// How spread wisp w is: the mean distance of its members' outer halves from its key hair.
float wispSpread(const FramePtr& frame, std::uint32_t w)
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
        window = wisp::test::openEditor();
        ASSERT_FALSE(HasFailure()) << "the window did not open";
        Document* doc = window->document();
        // A light groom keeps regrooms and the real-time simulation quick on two cores; no wind.
        doc->editRegionParameter(0, Param::Density, 2.0, false);
        doc->editRegionParameter(0, Param::LengthVariation, 0.0, false);
        doc->editParameter(Param::WindSpeed, 0.0, false);
        doc->editParameter(Param::Turbulence, 0.0, false);
        doc->undoStack()->clear();
        window->simulation()->pause();
        ASSERT_TRUE(wisp::test::waitUntil([&] { return window->simulation()->latestFrame() != nullptr; }));
        settle();
        runSteps(240); // hanging, at rest
        box = boundsOf(doc->head());
    }

    // Waits until the host has taken every edit: no regroom for a while.
    void settle()
    {
        QSignalSpy ready(window->simulation(), &SimulationHost::sceneReady);
        while (ready.wait(800 * WISP_SLOW_BUILD_FACTOR)) { }
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

} // namespace

TEST_F(StylingTest, CutShortensTheStrandsTheStrokeCrossesThereAndUndoRestoresThem)
{
    const float cutY = box.center().y - 0.10f;
    look(90.0f, { box.center().x, cutY, box.center().z }); // from the right, the eye level with the cut
    pick(Qt::Key_X, StyleBrush::Cut);
    const FramePtr before = frame();
    const Strands hanging = byIdentity(before);
    const Strands restBefore = byIdentity(before, true);
    const StyleEdits styleBefore = *document()->style();
    const int undoBefore = document()->undoStack()->count();

    // A horizontal snip across the hair that hangs at the right side, front to back.
    const float zFront = box.max.z + 0.02f, zBack = box.min.z - 0.02f;
    stroke({ { box.max.x + 0.05f, cutY, zFront }, { box.max.x + 0.05f, cutY, zBack } }, Qt::NoModifier, 20);
    EXPECT_EQ(document()->undoStack()->count(), undoBefore + 1) << "one stroke, one undo step";
    const FramePtr after = frame();
    const Strands restAfter = byIdentity(after, true);

    // Where each hanging strand crossed the cut's level (its first crossing from the root).
    const std::set<std::uint64_t> keys = keyIdentities(before);
    std::map<std::uint64_t, std::uint64_t> keyOf; // strand -> its wisp's key hair
    for (std::size_t i = 0; i < before->groomShape->identities.size(); ++i)
        keyOf[before->groomShape->identities[i]]
            = before->groomShape->identities[before->groomShape->keyOfWisp[before->groomShape->wispOf[i]]];
    int cut = 0, kept = 0;
    for (const auto& [id, points] : hanging) {
        std::optional<float> crossing;
        glm::vec3 at(0.0f);
        bool hangs = false;
        float arc = 0.0f;
        for (std::size_t j = 1; j < points.size() && !crossing; ++j) {
            const float a = points[j - 1].y - cutY, b = points[j].y - cutY;
            const float segment = glm::distance(points[j - 1], points[j]);
            if ((a > 0.0f) != (b > 0.0f)) {
                const float t = a / (a - b);
                crossing = arc + t * segment;
                at = glm::mix(points[j - 1], points[j], t);
                hangs = std::abs(a - b) > 0.7f * segment; // not lying along the blade (along the jaw)
            }
            arc += segment;
        }
        const float lengthBefore = strandLength(restBefore.at(id));
        const float lengthAfter = strandLength(restAfter.at(id));
        // X symmetry is on: the stroke also cuts, mirrored, the hair at the left side.
        const float side = std::abs(at.x - window->paintTool()->mirrorPlaneX());
        const float margin = 0.25f * (zFront - zBack); // the blade narrows toward the head: keep clear of its ends
        if (crossing && hangs && *crossing < lengthBefore - 0.02f && side > 0.35f * box.size().x
            && at.z < zFront - margin && at.z > zBack + margin) {
            // Plainly in view at a side: cut where the stroke crossed it (a key hair exactly; a
            // member, which rides beside its key at an offset, about there).
            EXPECT_NEAR(lengthAfter, *crossing, keys.count(id) ? 0.01f : 0.035f)
                << "strand " << id << " was " << lengthBefore << " crossing at " << at.x << " " << at.y << " " << at.z;
            EXPECT_LT(lengthAfter, lengthBefore - 0.01f) << "strand " << id;
            ++cut;
        } else if (!crossing && (keys.count(id) || !document()->style()->count(keyOf.at(id)))) {
            // Not reaching the stroke, in a wisp whose key hair was not cut: untouched. (Where the
            // key is cut, its wisp is: members ride beside it.)
            float moved = 0.0f;
            for (std::size_t j = 0; j < restAfter.at(id).size(); ++j)
                moved = std::max(moved, glm::distance(restAfter.at(id)[j], restBefore.at(id)[j]));
            EXPECT_EQ(moved, 0.0f) << "strand " << id << " changed";
            ++kept;
        }
    }
    EXPECT_GT(cut, 10) << "the stroke cut almost nothing: the test proves nothing";
    EXPECT_GT(kept, 50);
    EXPECT_LT(cut + kept, static_cast<int>(hanging.size())) << "the test measured every strand: suspicious";
    // The cut hair hangs no lower than the cut (with a little sway).
    runSteps(30);
    const Strands now = byIdentity(frame());
    const std::set<std::uint64_t> keysNow = keyIdentities(frame());
    for (const auto& [id, style] : *document()->style()) {
        if (keysNow.count(id)) {
            EXPECT_GT(now.at(id).back().y, cutY - 0.03f) << "cut key " << id << " still hangs below the cut";
        }
    }

    undo();
    EXPECT_EQ(*document()->style(), styleBefore);
    EXPECT_TRUE(byIdentity(frame(), true) == restBefore) << "undo did not give back the exact groom";
}

TEST_F(StylingTest, CombedHairFollowsTheStrokeAndStaysAfterFiveHundredSteps)
{
    const float combY = box.center().y - 0.08f;
    look(90.0f, { box.center().x, combY, box.center().z });
    pick(Qt::Key_C, StyleBrush::Comb);
    const FramePtr before = frame();
    const Strands tipsBefore = byIdentity(before);
    const StyleEdits styleBefore = *document()->style();
    const Strands restBefore = byIdentity(before, true);

    // Comb the side hair backward (-z), 6 cm.
    const glm::vec3 from = rightSide(0.08f, 0.02f), to = rightSide(0.08f, -0.04f);
    stroke({ from + glm::vec3(0.04f, 0, 0), to + glm::vec3(0.04f, 0, 0) }, Qt::NoModifier, 12);
    const StyleEdits& combed = *document()->style();
    ASSERT_GT(combed.size(), 3u) << "the comb caught no strand";
    for (const auto& [id, style] : combed)
        ASSERT_FALSE(style.shape.empty());

    auto meanTipShiftZ = [&](const FramePtr& f) {
        const Strands now = byIdentity(f);
        double sum = 0.0;
        for (const auto& [id, style] : combed)
            sum += now.at(id).back().z - tipsBefore.at(id).back().z;
        return sum / static_cast<double>(combed.size());
    };
    const double combedShift = meanTipShiftZ(frame());
    EXPECT_LT(combedShift, -0.02) << "the combed tips did not move back along the stroke";

    // Let it run: the rest shape was solved so that the hair stays where it was combed.
    SimulationHost* host = window->simulation();
    const std::uint64_t since = host->publishedFrames();
    host->play();
    ASSERT_TRUE(wisp::test::waitForFramesSince(*host, since, 500, 60000 * WISP_SLOW_BUILD_FACTOR));
    host->pause();
    QTest::qWait(50);
    const double shiftAfter = meanTipShiftZ(frame());
    EXPECT_LT(shiftAfter, 0.7 * combedShift)
        << "the hair sagged back: combed " << combedShift << ", now " << shiftAfter;
    EXPECT_GT(shiftAfter, 1.5 * combedShift) << "the hair kept moving past the comb";

    undo();
    EXPECT_EQ(*document()->style(), styleBefore);
    EXPECT_TRUE(byIdentity(frame(), true) == restBefore) << "undo did not give back the exact groom";
}

TEST_F(StylingTest, SprayedHairMovesLessInStrongWindThanUnsprayedHair)
{
    look(90.0f, { box.center().x, box.center().y - 0.05f, box.center().z });
    pick(Qt::Key_S, StyleBrush::Hairspray);
    // One side only, full strength, set in the Brush panel as an artist does.
    window->brushPanel()->mirrorBox()->click();
    ASSERT_FALSE(window->paintTool()->settings().mirrorX);
    QDoubleSpinBox* strength = window->brushPanel()->strengthBox();
    strength->setFocus();
    QTest::keyClick(strength, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(strength, QStringLiteral("1"));
    QTest::keyClick(strength, Qt::Key_Return);
    ASSERT_FLOAT_EQ(window->paintTool()->settings().strength, 1.0f);
    window->viewport()->setFocus();
    const StyleEdits styleBefore = *document()->style();
    const Strands restBefore = byIdentity(frame(), true);
    stroke({ rightSide(0.06f, 0.025f) + glm::vec3(0.03f, 0, 0), rightSide(0.06f, -0.025f) + glm::vec3(0.03f, 0, 0) });
    const StyleEdits sprayed = *document()->style();
    ASSERT_GT(sprayed.size(), 3u);
    double meanScale = 0.0;
    for (const auto& [id, style] : sprayed) {
        EXPECT_GT(style.stiffnessScale, 1.0f);
        EXPECT_FALSE(style.shape.empty()) << "hairspray keeps the shape the hair has";
        meanScale += style.stiffnessScale / static_cast<double>(sprayed.size());
    }
    EXPECT_GT(meanScale, 2.0);
    runSteps(60);
    const FramePtr calm = frame();
    document()->editParameter(Param::WindSpeed, 12.0, false);
    document()->editParameter(Param::WindAzimuth, 0.0, false);
    settle();
    runSteps(150);
    const Strands blown = byIdentity(frame());
    const Strands still = byIdentity(calm);
    double moved[2] = { 0, 0 };
    int count[2] = { 0, 0 };
    for (const std::uint64_t id : keyIdentities(calm)) {
        const bool isSprayed = sprayed.count(id) > 0;
        // Only hair hanging at the right side, where the spray went, compares like with like.
        if (still.at(id).back().x < box.center().x + 0.3f * box.size().x
            || still.at(id).back().y > box.center().y - 0.05f)
            continue;
        moved[isSprayed] += glm::distance(blown.at(id).back(), still.at(id).back());
        ++count[isSprayed];
    }
    ASSERT_GT(count[1], 3);
    ASSERT_GT(count[0], 3);
    const double unsprayed = moved[0] / count[0], sprayedMoved = moved[1] / count[1];
    EXPECT_GT(unsprayed, 0.02) << "the wind did not move the hair: the test proves nothing";
    EXPECT_LT(sprayedMoved, 0.5 * unsprayed);

    document()->editParameter(Param::WindSpeed, 0.0, false);
    document()->undoStack()->undo(); // the wind
    document()->undoStack()->undo();
    document()->undoStack()->undo(); // the azimuth
    undo(); // the spray, by its shortcut
    EXPECT_EQ(*document()->style(), styleBefore);
    EXPECT_TRUE(byIdentity(frame(), true) == restBefore) << "undo did not give back the exact groom";
}

TEST_F(StylingTest, WetWispsClumpAndSpreadAgainOnceDry)
{
    document()->editParameter(Param::DryingTime, 1.0, false); // a one-second half-life
    settle();
    look(90.0f, { box.center().x, box.center().y - 0.05f, box.center().z });
    pick(Qt::Key_W, StyleBrush::Wet);
    const FramePtr dry = frame();
    const StyleEdits styleBefore = *document()->style();
    stroke({ rightSide(0.0f, 0.06f) + glm::vec3(0.03f, 0, 0), rightSide(0.0f, -0.06f) + glm::vec3(0.03f, 0, 0),
        rightSide(0.12f, -0.06f) + glm::vec3(0.03f, 0, 0) });
    const StyleEdits wetted = *document()->style();
    ASSERT_GT(wetted.size(), 2u);
    const FramePtr wet = frame();
    ASSERT_FALSE(wet->wetness.empty()) << "the frame shows no wet hair";
    std::vector<std::uint32_t> touched;
    const GroomShape& g = *wet->groomShape;
    for (std::uint32_t w = 0; w < g.keyOfWisp.size(); ++w)
        if (wetted.count(g.identities[g.keyOfWisp[w]]) && wispSpread(dry, w) > 1e-3f)
            touched.push_back(w);
    ASSERT_GT(touched.size(), 2u);
    for (std::uint32_t w : touched) {
        EXPECT_GT(wet->wetness[g.keyOfWisp[w]], 0.3f);
        EXPECT_LT(wispSpread(wet, w), 0.7f * wispSpread(dry, w)) << "wet wisp " << w << " did not clump";
    }
    // About seven half-lives later the hair is dry, and spread as before.
    SimulationHost* host = window->simulation();
    host->play();
    ASSERT_TRUE(wisp::test::waitUntil([&] { return frame()->wetness.empty(); }, 30000 * WISP_SLOW_BUILD_FACTOR));
    host->pause();
    QTest::qWait(50);
    const FramePtr dried = frame();
    for (std::uint32_t w : touched)
        EXPECT_NEAR(wispSpread(dried, w), wispSpread(dry, w), 0.3f * wispSpread(dry, w) + 0.002f) << "wisp " << w;

    undo();
    EXPECT_EQ(*document()->style(), styleBefore);
}

TEST_F(StylingTest, PermGivesTheTouchedWispsTheSetCurlAndLeavesTheOthers)
{
    look(90.0f, { box.center().x, box.center().y - 0.05f, box.center().z });
    pick(Qt::Key_P, StyleBrush::Curl);
    // The curl is typed into the panel as an artist does.
    QDoubleSpinBox* radius = window->stylePanel()->curlRadiusBox();
    QDoubleSpinBox* turns = window->stylePanel()->curlTurnsBox();
    for (auto [box, text] : { std::pair{ radius, QStringLiteral("8") }, std::pair{ turns, QStringLiteral("12") } }) {
        box->setFocus();
        QTest::keyClick(box, Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(box, text);
        QTest::keyClick(box, Qt::Key_Return);
    }
    ASSERT_FLOAT_EQ(window->styleTool()->curlRadiusMetres(), 0.008f);
    ASSERT_FLOAT_EQ(window->styleTool()->curlTurnsPerMetre(), 12.0f);
    window->viewport()->setFocus();

    const FramePtr before = frame();
    const Strands restBefore = byIdentity(before, true);
    const StyleEdits styleBefore = *document()->style();
    stroke({ rightSide(0.02f, 0.05f) + glm::vec3(0.03f, 0, 0), rightSide(0.02f, -0.05f) + glm::vec3(0.03f, 0, 0) });
    const StyleEdits permed = *document()->style();
    ASSERT_GT(permed.size(), 2u);
    const FramePtr after = frame();
    const Strands restAfter = byIdentity(after, true);
    const std::set<std::uint64_t> keys = keyIdentities(after);
    int curled = 0, untouched = 0;
    for (const auto& [id, rest] : restAfter) {
        if (!keys.count(id))
            continue;
        if (permed.count(id)) {
            EXPECT_FLOAT_EQ(permed.at(id).curlRadiusMetres, 0.008f);
            EXPECT_FLOAT_EQ(permed.at(id).curlTurnsPerMetre, 12.0f);
            // The period: the strand winds about its own centre line 12 times per metre. The centre
            // line is the running mean over one period; the winding is summed turn by turn.
            const float length = strandLength(rest);
            const std::size_t window
                = std::max<std::size_t>(3, static_cast<std::size_t>(std::lround((rest.size() - 1) / (12.0f * length))));
            double angle = 0.0;
            glm::vec3 previous(0.0f);
            for (std::size_t j = window / 2; j + window / 2 < rest.size(); ++j) {
                glm::vec3 centre(0.0f);
                for (std::size_t k = j - window / 2; k <= j + window / 2; ++k)
                    centre += rest[k];
                centre /= static_cast<float>(2 * (window / 2) + 1);
                const glm::vec3 tangent = glm::normalize(rest[j + window / 2] - rest[j - window / 2]);
                glm::vec3 offset = rest[j] - centre;
                offset -= glm::dot(offset, tangent) * tangent;
                if (glm::length(previous) > 0.0f && glm::length(offset) > 1e-4f)
                    angle += std::acos(
                        std::clamp(glm::dot(glm::normalize(previous), glm::normalize(offset)), -1.0f, 1.0f));
                if (glm::length(offset) > 1e-4f)
                    previous = offset;
            }
            const double expectedTurns = 12.0 * length * (rest.size() - 2 * (window / 2)) / rest.size();
            EXPECT_NEAR(angle / (2.0 * M_PI), expectedTurns, 0.3 * expectedTurns) << "key " << id;
            ++curled;
        } else {
            EXPECT_TRUE(rest == restBefore.at(id)) << "untouched key " << id << " changed";
            ++untouched;
        }
    }
    EXPECT_GT(curled, 2);
    EXPECT_GT(untouched, 20);

    undo();
    EXPECT_EQ(*document()->style(), styleBefore);
    EXPECT_TRUE(byIdentity(frame(), true) == restBefore) << "undo did not give back the exact groom";
}

TEST_F(StylingTest, TheDryerBlowsTheHairInItsConeAwayFromTheCursorAndDriesIt)
{
    document()->editParameter(Param::DryingTime, 3600.0, false); // no drying but the dryer's
    settle();
    // Wet the right side first.
    look(90.0f, { box.center().x, box.center().y - 0.05f, box.center().z });
    pick(Qt::Key_W, StyleBrush::Wet);
    stroke({ rightSide(-0.02f, 0.08f) + glm::vec3(0.03f, 0, 0), rightSide(-0.02f, -0.08f) + glm::vec3(0.03f, 0, 0),
        rightSide(0.12f, -0.08f) + glm::vec3(0.03f, 0, 0), rightSide(0.12f, 0.08f) + glm::vec3(0.03f, 0, 0) });
    const StyleEdits wetStyle = *document()->style();
    ASSERT_GT(wetStyle.size(), 3u);
    runSteps(120); // wet hair is softer: let it settle

    // From the front, aim the dryer at the hair beside the right cheek: the air blows backward.
    const glm::vec3 aim{ box.center().x + 0.25f * box.size().x, box.center().y - 0.03f, box.center().z }; // the cheek
    look(0.0f, { box.center().x, aim.y, box.center().z }, 0.8f);
    pick(Qt::Key_D, StyleBrush::BlowDry);
    const FramePtr calm = frame();
    const int undoBefore = document()->undoStack()->count();
    Viewport* view = window->viewport();
    const QPoint at = screenOf(aim);
    const glm::vec3 axis = view->rayAt(at).direction;
    SimulationHost* host = window->simulation();
    QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, at);
    const std::uint64_t since = host->publishedFrames();
    host->play();
    ASSERT_TRUE(wisp::test::waitForFramesSince(*host, since, 90, 30000 * WISP_SLOW_BUILD_FACTOR));
    host->pause();
    QTest::qWait(50);
    const FramePtr blown = frame();
    QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, at);
    settle();

    // In a cone: keys whose outer half was in the air of the dryer, or of its mirror (X symmetry is
    // on, so a second dryer blows at the left side).
    HairDryer dryer;
    dryer.direction = axis;
    const auto hit = window->paintTool()->hitAt(at);
    ASSERT_TRUE(hit.has_value()) << "the dryer was not aimed at the head";
    const float hitDepth = glm::dot(hit->point - view->rayAt(at).origin, axis);
    dryer.nozzle = view->rayAt(at).origin + axis * (hitDepth - kDryerDistanceMetres);
    const TriangleMesh& head = document()->head();
    const float extent = std::max({ box.size().x, box.size().y, box.size().z });
    const SignedDistanceField field = SignedDistanceField::bake(head, extent / 96.0f, 0.1f * extent + 0.01f);
    HairDryer mirror = dryer;
    mirror.nozzle = mirroredPoint(dryer.nozzle, window->paintTool()->mirrorPlaneX());
    mirror.direction = mirroredDirection(dryer.direction);
    const Strands still = byIdentity(calm), moved = byIdentity(blown);
    const GroomShape& g = *calm->groomShape;
    double along[2] = { 0, 0 }, wetness[2] = { 0, 0 };
    int count[2] = { 0, 0 }, mirrored = 0;
    for (std::uint32_t w = 0; w < g.keyOfWisp.size(); ++w) {
        const std::uint32_t key = g.keyOfWisp[w];
        const std::uint64_t id = g.identities[key];
        const auto& strand = still.at(id);
        float air[2] = { 0.0f, 0.0f }, anyAir = 0.0f;
        for (int d = 0; d < 2; ++d) {
            const HairDryer& one = d == 0 ? dryer : mirror;
            for (std::size_t j = strand.size() / 2; j < strand.size(); ++j)
                air[d] += glm::length(dryerAirAt(one, strand[j], &field))
                    / static_cast<float>(strand.size() - strand.size() / 2);
            for (const glm::vec3& p : strand)
                anyAir = std::max(anyAir, glm::length(dryerAirAt(one, p, &field)));
        }
        const int which = air[1] > air[0] ? 1 : 0;
        if (air[which] < 1.0f && anyAir > 0.3f)
            continue; // a cone's edge (outside: no more than a breath of air anywhere on it)
        const bool inCone = air[which] >= 1.0f;
        mirrored += inCone && which == 1;
        along[inCone] += glm::dot(moved.at(id).back() - strand.back(), (which == 0 ? dryer : mirror).direction);
        ++count[inCone];
        if (inCone && wetStyle.count(id)) { // how wet it is now, of how wet the brush made it
            wetness[0] += wetStyle.at(id).wetness;
            wetness[1] += blown->wetness.empty() ? 0.0 : blown->wetness[key];
        }
    }
    EXPECT_GT(mirrored, 0) << "the mirrored dryer blew on nothing";
    ASSERT_GT(count[1], 2) << "no wet strand in the cone";
    ASSERT_GT(count[0], 2);
    EXPECT_GT(along[1] / count[1], 0.01) << "the hair in the cone did not move away from the cursor";
    EXPECT_LT(along[0] / count[0], 0.3 * along[1] / count[1]);
    ASSERT_GT(wetness[0], 0.0) << "no wet hair in the cones";
    EXPECT_LT(wetness[1], 0.6 * wetness[0]) << "the dryer did not dry the hair it blew on";

    // What it dried is one undo step, and undo brings the wetness back exactly.
    EXPECT_EQ(document()->undoStack()->count(), undoBefore + 1);
    EXPECT_NE(*document()->style(), wetStyle);
    undo();
    EXPECT_EQ(*document()->style(), wetStyle);
}

TEST_F(StylingTest, GrowAndShrinkChangeTheLengthUnderTheBrushAndToolsAreExclusive)
{
    look(90.0f, { box.center().x, box.center().y - 0.05f, box.center().z });
    pick(Qt::Key_G, StyleBrush::Length);
    const Strands restBefore = byIdentity(frame(), true);
    QSignalSpy said(window->statusBar(), &QStatusBar::messageChanged);
    stroke({ rightSide(0.05f, 0.05f) + glm::vec3(0.03f, 0, 0), rightSide(0.05f, -0.05f) + glm::vec3(0.03f, 0, 0) });
    const StyleEdits grown = *document()->style();
    ASSERT_GT(grown.size(), 3u);
    // The status bar said what the stroke did (a slow build may have cleared it again since).
    bool told = false;
    for (const QList<QVariant>& message : said)
        told = told || message.value(0).toString().contains(QStringLiteral("strands changed"));
    EXPECT_TRUE(told) << "the status bar did not say what the stroke did";
    const Strands restGrown = byIdentity(frame(), true);
    const std::set<std::uint64_t> keys = keyIdentities(frame());
    double grownBy = 0.0;
    int grownKeys = 0;
    for (const auto& [id, style] : grown) {
        if (!keys.count(id))
            continue; // members ride beside their keys: their drawn length follows the key's
        EXPECT_NEAR(strandLength(restGrown.at(id)), style.lengthMetres, 0.001f) << id;
        EXPECT_GT(strandLength(restGrown.at(id)), strandLength(restBefore.at(id))) << id;
        grownBy += strandLength(restGrown.at(id)) - strandLength(restBefore.at(id));
        ++grownKeys;
    }
    ASSERT_GT(grownKeys, 2);
    EXPECT_GT(grownBy / grownKeys, 0.005) << "a stroke grew the hair by less than 5 mm";
    // Ctrl shrinks, on the same hair.
    stroke({ rightSide(0.05f, 0.05f) + glm::vec3(0.03f, 0, 0), rightSide(0.05f, -0.05f) + glm::vec3(0.03f, 0, 0) },
        Qt::ControlModifier);
    const Strands restShrunk = byIdentity(frame(), true);
    int shorter = 0;
    for (const auto& [id, style] : *document()->style())
        shorter += keys.count(id) && strandLength(restShrunk.at(id)) < strandLength(restGrown.at(id)) - 0.002f;
    EXPECT_GT(shorter, 2);
    EXPECT_EQ(document()->undoStack()->count(), 2);

    // Painting growth and styling never run at once; the growth weights' tint shows only for painting.
    EXPECT_FALSE(window->viewport()->showGrowthOverlay());
    QTest::keyClick(window->viewport(), Qt::Key_B);
    EXPECT_TRUE(window->paintTool()->isActive());
    EXPECT_FALSE(window->styleTool()->isActive());
    EXPECT_TRUE(window->viewport()->showGrowthOverlay());
    QTest::keyClick(window->viewport(), Qt::Key_C);
    EXPECT_FALSE(window->paintTool()->isActive());
    EXPECT_EQ(window->styleTool()->brush(), StyleBrush::Comb);
    EXPECT_TRUE(window->stylePanel()->actionFor(StyleBrush::Comb)->isChecked());
    EXPECT_FALSE(window->stylePanel()->actionFor(StyleBrush::Length)->isChecked());

    undo();
    undo();
    EXPECT_TRUE(document()->style()->empty());
    EXPECT_TRUE(byIdentity(frame(), true) == restBefore) << "undo did not give back the exact groom";
}

TEST_F(StylingTest, EditsComeBackWithTheProjectAndPresetsLeaveThem)
{
    look(90.0f, { box.center().x, box.center().y - 0.08f, box.center().z });
    pick(Qt::Key_X, StyleBrush::Cut);
    stroke({ { box.max.x + 0.05f, box.center().y - 0.08f, box.max.z },
               { box.max.x + 0.05f, box.center().y - 0.08f, box.min.z } },
        Qt::NoModifier, 16);
    pick(Qt::Key_P, StyleBrush::Curl);
    stroke({ rightSide(0.0f, 0.05f) + glm::vec3(0.03f, 0, 0), rightSide(0.0f, -0.05f) + glm::vec3(0.03f, 0, 0) });
    const StyleEdits styled = *document()->style();
    ASSERT_GT(styled.size(), 10u);
    const Strands rest = byIdentity(frame(), true);

    // A preset changes the look's parameters, never the salon edits.
    io::Preset preset = document()->toPreset(QStringLiteral("Same"));
    preset.parameters.set(Param::Gravity, 5.0);
    document()->applyPreset(preset);
    settle();
    EXPECT_EQ(*document()->style(), styled);

    // Saved, a new project (no edits), opened again: the edits and the groom they make are back.
    window->fileMenu()->setInteractive(false);
    ProjectController* projects = window->fileMenu()->projects();
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("styled.wisp"));
    ASSERT_TRUE(projects->saveAs(path)) << projects->lastError().toStdString();
    ASSERT_TRUE(projects->newProject());
    settle();
    EXPECT_TRUE(document()->style()->empty());
    ASSERT_TRUE(projects->open(path)) << projects->lastError().toStdString();
    settle();
    EXPECT_EQ(*document()->style(), styled);
    // The same density as the saved groom: compare the styled strands' rest shapes.
    const Strands reopened = byIdentity(frame(), true);
    int compared = 0;
    for (const auto& [id, style] : styled)
        if (reopened.count(id) && rest.count(id)) {
            EXPECT_EQ(strandLength(reopened.at(id)), strandLength(rest.at(id))) << id;
            ++compared;
        }
    EXPECT_EQ(compared, static_cast<int>(styled.size()));
    document()->undoStack()->setClean();
}

TEST_F(StylingTest, AStrokeNeverLeavesAnEditTheProjectFileWouldRefuse)
{
    const std::uint64_t id = frame()->groomShape->identities[0];
    document()->beginStyleStroke();
    document()->strokeStyle()[id].wetness = 3.0f; // what no tool should make
    document()->strokeStyle()[id + 1].lengthMetres = 0.1f;
    document()->styleStrokeUpdated();
    EXPECT_EQ(document()->endStyleStroke(QStringLiteral("Test")), 1);
    EXPECT_EQ(document()->style()->count(id), 0u);
    ASSERT_EQ(document()->style()->count(id + 1), 1u);
    EXPECT_EQ(document()->style()->at(id + 1).lengthMetres, 0.1f);
    io::Project project = document()->toProject();
    QTemporaryDir dir;
    EXPECT_TRUE(io::writeProject(dir.filePath(QStringLiteral("ok.wisp")).toStdString(), project));
    document()->undoStack()->setClean();
}

// Issue 11: after File ▸ New, a cut at eyebrow height and the bundled Curly preset (more segments,
// another density and wisp size) applied from the preset browser, no strand may stick out: every
// drawn strand hangs under gravity within its length of its root, and keeps the length its edit
// (or its groom) gives it.
TEST_F(StylingTest, CutThenCurlyPresetLeavesNoStrandStickingOut)
{
    window->fileMenu()->setInteractive(false);
    SimulationHost* host = window->simulation();
    // File ▸ New, by its shortcut: the default groom.
    const std::uint64_t groomBefore = frame()->groomVersion;
    QTest::keyClick(window->viewport(), Qt::Key_N, Qt::ControlModifier);
    ASSERT_TRUE(wisp::test::waitUntil([&] { return frame()->groomVersion > groomBefore; }));
    settle();
    ASSERT_FALSE(host->isPlaying());
    runSteps(150); // hanging

    // The cut: from the front, a horizontal stroke across the face at eyebrow height (the brow
    // ridge of the built-in head), both sides (X symmetry).
    const float browY = box.min.y + 0.62f * box.size().y;
    look(0.0f, { box.center().x, browY, box.center().z }, 0.6f);
    pick(Qt::Key_X, StyleBrush::Cut);
    const float zFront = box.max.z + 0.03f;
    stroke({ { box.min.x - 0.04f, browY, zFront }, { box.max.x + 0.04f, browY, zFront } }, Qt::NoModifier, 24);
    const StyleEdits cut = *document()->style();
    ASSERT_GT(cut.size(), 20u) << "the stroke cut almost nothing: the test proves nothing";

    // Presets ▸ Curly ▸ Apply, in the dock.
    auto* dock = window->findChild<QDockWidget*>(QStringLiteral("presetsDock"));
    ASSERT_NE(dock, nullptr);
    dock->show();
    dock->raise();
    QTest::qWait(50);
    QListWidget* list = window->presetBrowser()->listWidget();
    int row = -1;
    for (int r = 0; r < list->count(); ++r)
        if (list->item(r)->text() == QStringLiteral("Curly"))
            row = r;
    ASSERT_GE(row, 0);
    list->scrollToItem(list->item(row));
    const QRect rect = list->visualItemRect(list->item(row));
    ASSERT_FALSE(rect.isEmpty());
    QTest::mouseClick(list->viewport(), Qt::LeftButton, Qt::NoModifier, rect.center());
    ASSERT_EQ(list->currentRow(), row);
    ASSERT_TRUE(window->presetBrowser()->applyButton()->isEnabled());
    QTest::mouseClick(window->presetBrowser()->applyButton(), Qt::LeftButton);
    settle();
    ASSERT_EQ(document()->parameters().getInt(Param::Segments), 48) << "the Curly preset was not applied";
    EXPECT_EQ(*document()->style(), cut) << "a preset leaves the salon edits";
    ASSERT_EQ(frame()->strands.strand(0).size(), 49u);
    runSteps(120);

    const FramePtr f = frame();
    const GroomShape& g = *f->groomShape;
    const HairCurves& drawn = f->strands;
    ASSERT_EQ(drawn.strandCount(), g.lengths.size());
    int tooFar = 0, standing = 0, wrongLength = 0, keysMeasured = 0, cutKeys = 0;
    float worstReach = 0.0f, worstRise = 0.0f;
    for (std::size_t i = 0; i < drawn.strandCount(); ++i) {
        const auto s = drawn.strand(i);
        const std::uint32_t key = g.keyOfWisp[g.wispOf[i]];
        // A member rides beside its key: its points are within its length plus twice its root's
        // offset from the key's root (the offset turned with the key, then clumped) of its root.
        const float offset = i == key ? 0.0f : glm::distance(s.front(), drawn.strand(key).front());
        const float allowed = 1.01f * g.lengths[i] + 2.0f * offset + 1e-4f;
        float reach = 0.0f;
        for (const glm::vec3& p : s)
            reach = std::max(reach, glm::distance(p, s.front()));
        if (reach > allowed) {
            if (tooFar < 5)
                ADD_FAILURE() << "strand " << i << " (length " << g.lengths[i] << ") reaches " << reach
                              << " m from its root";
            ++tooFar;
        }
        worstReach = std::max(worstReach, reach - allowed);
        // Hanging under gravity: a strand longer than 8 cm ends no higher than where it grows (give
        // or take the spring of curls parted at the crown: 4 cm); one standing out from the scalp
        // ends most of its length above it.
        const float rise = s.back().y - s.front().y;
        if (g.lengths[i] > 0.08f && rise > 0.04f) {
            if (standing < 5)
                ADD_FAILURE() << "strand " << i << " (length " << g.lengths[i] << ") ends " << rise
                              << " m above its root: it sticks out";
            ++standing;
        }
        worstRise = std::max(worstRise, g.lengths[i] > 0.08f ? rise : 0.0f);
        if (i == key) {
            // Simulated, so inextensible: drawn as long as its rest shape. That is as long as its
            // groom says, or less (a polyline round a helix whose radius ramps up from the root),
            // but no shorter than the helix's axis: 1 / sqrt(1 + (2 pi r T)^2) = 0.66 of it for Curly.
            ++keysMeasured;
            const float restLength = strandLength(g.rest.strand(i));
            if (std::abs(strandLength(s) - restLength) > 0.01f * restLength + 1e-4f
                || restLength > g.lengths[i] * 1.001f || restLength < 0.65f * g.lengths[i]) {
                ++wrongLength;
            }
            const auto edit = cut.find(g.identities[i]);
            if (edit != cut.end() && edit->second.lengthMetres > 0.0f) {
                EXPECT_FLOAT_EQ(g.lengths[i], edit->second.lengthMetres) << "cut key " << i;
                ++cutKeys;
            }
        }
        // No member is longer than its key by more than the groom's length variation allows.
        if (i != key) {
            EXPECT_LE(g.lengths[i], g.lengths[key] * 1.5f + 1e-4f)
                << "member " << i << " of a key " << g.lengths[key] << " long";
        }
    }
    EXPECT_EQ(tooFar, 0) << "worst by " << worstReach << " m";
    EXPECT_EQ(standing, 0) << "worst rise " << worstRise << " m";
    EXPECT_EQ(wrongLength, 0) << "of " << keysMeasured << " keys";
    EXPECT_GT(cutKeys, 0) << "no cut key hair after the preset: the test proves nothing";
    document()->undoStack()->setClean();
}

// Before: the comb picked only key hairs under the ring (11 of the strands across the face), so most
// of the hair it visibly covered stayed where it was.
TEST_F(StylingTest, TheCombCatchesTheStrandsItsRingCovers)
{
    window->paintTool()->setMirror(false);
    const float combY = box.center().y - 0.06f;
    look(90.0f, { box.center().x, combY, box.center().z });
    pick(Qt::Key_C, StyleBrush::Comb);
    const FramePtr before = frame();
    const GroomShape& shape = *before->groomShape;

    // What lies under the ring where the stroke starts, measured here: every drawn strand with a
    // point within the radius of the cursor's ray, in front of the head's surface under it.
    const glm::vec3 from = rightSide(0.06f, 0.02f) + glm::vec3(0.04f, 0, 0);
    const glm::vec3 to = rightSide(0.06f, -0.03f) + glm::vec3(0.04f, 0, 0);
    Viewport* view = window->viewport();
    const QPoint at = screenOf(from);
    const ViewRay ray = view->rayAt(at);
    const float radius = window->paintTool()->settings().radiusMetres;
    const auto hit = window->paintTool()->hitAt(at);
    ASSERT_TRUE(hit.has_value()) << "the stroke does not start over the head";
    const float surface = glm::dot(hit->point - ray.origin, ray.direction) + radius;
    std::set<std::uint32_t> under;
    for (std::uint32_t s = 0; s < before->strands.strandCount(); ++s)
        for (const glm::vec3& p : before->strands.strand(s)) {
            const float t = glm::dot(p - ray.origin, ray.direction);
            if (t > 0.0f && t < surface && glm::length(p - ray.origin - t * ray.direction) < 0.98f * radius) {
                under.insert(s);
                break;
            }
        }
    ASSERT_GE(under.size(), 20u) << "too little hair under the ring: the test proves nothing";

    QSignalSpy said(window->statusBar(), &QStatusBar::messageChanged);
    stroke({ from, to }, Qt::NoModifier, 6);
    // Caught: the strands whose wisp's key hair the comb moved (members follow their key).
    std::set<std::uint64_t> combedKeys;
    for (const auto& [id, style] : *document()->style())
        if (!style.shape.empty())
            combedKeys.insert(id);
    std::set<std::uint32_t> caught;
    for (std::uint32_t s = 0; s < shape.wispOf.size(); ++s)
        if (combedKeys.count(shape.identities[shape.keyOfWisp[shape.wispOf[s]]]))
            caught.insert(s);
    int missed = 0;
    for (std::uint32_t s : under)
        missed += caught.count(s) ? 0 : 1;
    EXPECT_LE(missed, static_cast<int>(under.size() / 20))
        << missed << " of the " << under.size() << " strands under the ring were not caught";
    EXPECT_LE(caught.size(), 3 * under.size()) << "the comb caught far more than its ring covers";
    // The status bar says how many strands the stroke moved (a warning may have followed since).
    QStringList messages;
    for (const QList<QVariant>& message : said)
        messages << message.value(0).toString();
    EXPECT_TRUE(messages.contains(QStringLiteral("Comb: %1 strands changed").arg(caught.size())))
        << messages.join(QStringLiteral(" | ")).toStdString();
}

// Before: a stroke that changed nothing left its warning on the status bar through the next stroke.
TEST_F(StylingTest, ANewStrokeClearsTheLastStrokesWarning)
{
    look(90.0f, { box.center().x, box.center().y - 0.05f, box.center().z });
    pick(Qt::Key_X, StyleBrush::Cut);
    // Far above the head: nothing to cut.
    stroke({ glm::vec3(box.max.x + 0.05f, box.max.y + 0.15f, box.center().z + 0.05f),
        glm::vec3(box.max.x + 0.05f, box.max.y + 0.15f, box.center().z - 0.05f) });
    ASSERT_EQ(window->statusBar()->currentMessage(), QStringLiteral("Cut: no strand under the brush changed"));
    pick(Qt::Key_W, StyleBrush::Wet);
    Viewport* view = window->viewport();
    const QPoint at = screenOf(rightSide(0.05f) + glm::vec3(0.03f, 0, 0));
    QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, at);
    EXPECT_TRUE(window->statusBar()->currentMessage().isEmpty())
        << "the new stroke still shows: " << window->statusBar()->currentMessage().toStdString();
    QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, at);
    settle();
    EXPECT_TRUE(window->statusBar()->currentMessage().startsWith(QStringLiteral("Wet: ")));
}

TEST_F(StylingTest, TheDryerBlowsFromTheEyeTowardTheSurfaceAndShowsItsCone)
{
    const glm::vec3 aim{ box.center().x + 0.25f * box.size().x, box.center().y - 0.03f, box.center().z };
    look(0.0f, { box.center().x, aim.y, box.center().z }, 0.8f);
    pick(Qt::Key_D, StyleBrush::BlowDry);
    Viewport* view = window->viewport();
    const QPoint at = screenOf(aim);
    QTest::mouseMove(view, at);
    ASSERT_TRUE(wisp::test::waitUntil([&] { return view->brushCursor().has_value(); }, 2000));
    const BrushCursor cursor = *view->brushCursor();
    EXPECT_TRUE(cursor.dryer) << "the dryer shows no cone";
    const ViewRay ray = view->rayAt(at);
    const auto hit = window->paintTool()->hitAt(at);
    ASSERT_TRUE(hit.has_value());
    const float hitDepth = glm::dot(hit->point - ray.origin, ray.direction);
    // The cone: from a nozzle between the eye and the surface to a rim around the aimed point.
    EXPECT_NEAR(glm::distance(cursor.dryerNozzle, hit->point), kDryerDistanceMetres, 1e-4f);
    EXPECT_LT(glm::distance(cursor.dryerNozzle, ray.origin), hitDepth);
    EXPECT_GT(cursor.radiusMetres, 0.02f);
    const std::vector<GuideVertex> cone
        = buildDryerCone(cursor.dryerNozzle, cursor.centre, cursor.dryerHalfAngleRadians, 0.002f, 1.0f);
    EXPECT_FALSE(cone.empty());

    QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, at);
    const std::vector<HairDryer> dryers = window->styleTool()->dryers();
    ASSERT_FALSE(dryers.empty()) << "no dryer blows while the button is held";
    const HairDryer& dryer = dryers.front();
    const glm::vec3 eyeToSurface = glm::normalize(hit->point - ray.origin);
    EXPECT_GT(glm::dot(dryer.direction, eyeToSurface), 0.9999f)
        << "the dryer does not blow from the eye at the surface";
    EXPECT_LT(glm::dot(dryer.direction, hit->normal), 0.0f) << "the dryer blows away from the surface";
    // The air reaches the aimed point, on the axis, at speed.
    EXPECT_GT(glm::length(dryerAirAt(dryer, hit->point)), 5.0f);
    if (const char* folder = std::getenv("WISP_TEST_SCREENSHOT_DIR")) {
        QTest::qWait(200);
        // The window, with the viewport's GL frame read back into its place (grab() leaves it blank).
        QImage shot = window->grab().toImage();
        QPainter painter(&shot);
        painter.drawImage(view->mapTo(window.get(), QPoint(0, 0)), view->grabFramebuffer());
        painter.end();
        shot.save(QString::fromLocal8Bit(folder) + QStringLiteral("/dryer-cone.png"));
    }
    QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, at);
    EXPECT_TRUE(window->styleTool()->dryers().empty());
    settle();
}
