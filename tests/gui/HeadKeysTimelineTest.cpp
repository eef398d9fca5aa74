// The head's keys and the timeline share one current time (issue 17), as Blender's dopesheet and
// timeline do: scrubbing the timeline to frame f makes Set Key key at (f - 1) / fps seconds,
// selecting a key takes the timeline to its frame, and moving a key (its time typed into the
// Motion panel) is one undo step that the timeline follows. Real key and mouse events; the live
// simulation is paused and nothing waits on the clock.
#include "GuiTestSupport.h"
#include "app/editor/Document.h"
#include "app/editor/MainWindow.h"
#include "app/editor/MotionPanel.h"
#include "app/editor/SimulationHost.h"
#include "app/editor/TimelineDock.h"
#include "sim/motion/FrameTime.h"
#include "widgets/Viewport.h"

#include <QAction>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QSlider>
#include <QTest>
#include <QUndoStack>

#include <gtest/gtest.h>

#include <algorithm>

using namespace wisp;
using namespace wisp::test;

namespace {

class HeadKeysTimelineTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        window = openEditor();
        ASSERT_TRUE(waitForFirstFrame(*window->simulation()));
        if (window->playAction()->isChecked())
            window->playAction()->trigger();
        ASSERT_TRUE(waitUntil([&] { return !window->simulation()->isPlaying(); }));
        doc()->undoStack()->clear();
    }
    void TearDown() override
    {
        if (window)
            doc()->undoStack()->setClean(); // close without a prompt
    }
    Document* doc() const { return window->document(); }
    TimelineDock* dock() const { return window->timelineDock(); }
    MotionPanel* panel() const { return window->motionPanel(); }
    std::vector<double> keyTimes() const
    {
        std::vector<double> out;
        for (const HeadKey& key : doc()->headMotion().keys())
            out.push_back(key.timeSeconds);
        return out;
    }
    void setKey() { QTest::mouseClick(panel()->setKeyButton(), Qt::LeftButton); }

    std::unique_ptr<MainWindow> window;
};

} // namespace

TEST_F(HeadKeysTimelineTest, SetKeyKeysAtTheScrubbedFrameAndSelectingOrMovingAKeyMovesTheScrub)
{
    const double fps = doc()->timeline().fps;
    ASSERT_EQ(fps, 24.0);
    ASSERT_EQ(doc()->timeline().lastFrame, 48);
    EXPECT_FALSE(dock()->isOnFrame());
    EXPECT_EQ(dock()->frameLabel()->text(), QStringLiteral("live"));

    // Before any bake the slider sets the frame: 11 steps right of frame 1 is frame 12.
    ASSERT_TRUE(dock()->slider()->isEnabled());
    dock()->slider()->setFocus();
    QTest::keyClick(dock()->slider(), Qt::Key_Home);
    for (int i = 0; i < 11; ++i)
        QTest::keyClick(dock()->slider(), Qt::Key_Right);
    ASSERT_EQ(dock()->currentFrame(), 12);
    EXPECT_TRUE(dock()->isOnFrame());
    EXPECT_EQ(dock()->frameLabel()->text(), QStringLiteral("frame 12 (not baked)"));
    setKey();
    EXPECT_EQ(keyTimes(), std::vector<double>{ 11.0 / 24.0 });

    QTest::keyClick(dock()->slider(), Qt::Key_End);
    ASSERT_EQ(dock()->currentFrame(), 48);
    setKey();
    QTest::keyClick(dock()->slider(), Qt::Key_Home);
    setKey();
    EXPECT_EQ(keyTimes(), (std::vector<double>{ 0.0, 11.0 / 24.0, 47.0 / 24.0 }));
    EXPECT_EQ(doc()->undoStack()->count(), 3);

    // Selecting a key takes the timeline to its frame.
    QListWidget* keys = panel()->keyList();
    keys->setFocus();
    QTest::keyClick(keys, Qt::Key_End);
    EXPECT_EQ(dock()->currentFrame(), 48);
    QTest::keyClick(keys, Qt::Key_Up);
    ASSERT_EQ(keys->currentRow(), 1);
    EXPECT_EQ(dock()->currentFrame(), 12);
    EXPECT_NEAR(panel()->keyTimeBox()->value(), 11.0 / 24.0, 0.0005); // the box shows milliseconds

    // Moving the selected key to 1 s: one undo step, the timeline follows it to frame 25.
    QDoubleSpinBox* time = panel()->keyTimeBox();
    time->setFocus();
    QTest::keyClick(time, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(time, QStringLiteral("1"));
    QTest::keyClick(time, Qt::Key_Return);
    EXPECT_EQ(keyTimes(), (std::vector<double>{ 0.0, 1.0, 47.0 / 24.0 }));
    EXPECT_EQ(doc()->undoStack()->count(), 4);
    EXPECT_EQ(doc()->undoStack()->undoText(), QStringLiteral("Move Head Key"));
    EXPECT_EQ(dock()->currentFrame(), frameAtSeconds(1.0, fps));
    EXPECT_EQ(dock()->currentFrame(), 25);
    doc()->undoStack()->undo();
    EXPECT_EQ(keyTimes(), (std::vector<double>{ 0.0, 11.0 / 24.0, 47.0 / 24.0 }));
    doc()->undoStack()->redo();
    EXPECT_EQ(keyTimes(), (std::vector<double>{ 0.0, 1.0, 47.0 / 24.0 }));

    // A typed time lands on the nearest frame: the box shows milliseconds, so typing back the
    // 0.458 it shows for frame 12 puts the key on frame 12 exactly (11/24 s), not 0.3 ms off it.
    ASSERT_EQ(keys->currentRow(), 1);
    time->setFocus();
    QTest::keyClick(time, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(time, QStringLiteral("0.458"));
    QTest::keyClick(time, Qt::Key_Return);
    EXPECT_EQ(keyTimes(), (std::vector<double>{ 0.0, 11.0 / 24.0, 47.0 / 24.0 }));
    EXPECT_EQ(dock()->currentFrame(), 12);

    // Esc goes back to live: Set Key keys at the live simulation's time again (on a frame).
    window->viewport()->setFocus();
    QTest::keyClick(window->viewport(), Qt::Key_Escape);
    EXPECT_FALSE(dock()->isOnFrame());
    EXPECT_EQ(dock()->frameLabel()->text(), QStringLiteral("live"));
    for (int i = 0; i < 40; ++i) { // past 1.5 s of live time, where no key is yet
        const std::uint64_t before = window->simulation()->publishedFrames();
        window->simulation()->stepOnce();
        ASSERT_TRUE(waitForFramesSince(*window->simulation(), before, 1));
    }
    const double live = window->simulation()->latestFrame()->simulatedSeconds;
    setKey();
    const std::vector<double> times = keyTimes();
    EXPECT_NE(std::find(times.begin(), times.end(), snappedToFrame(live, fps)), times.end())
        << "live time " << live << " s";
}
