// The timeline dock as an artist uses it, with real mouse and key events: the range typed into its
// spin boxes, a bake of a few frames of a light groom, the slider scrubbed to a frame that the
// viewport then draws exactly as baked, playback of the cache, Esc back to live, an edit marking
// the cache stale, Cancel, the memory bound's refusal, and the range kept by save and reopen.
// Waits are bounded and counted in frames, never in time.
#include "GuiTestSupport.h"
#include "app/editor/BakeController.h"
#include "app/editor/Document.h"
#include "app/editor/FileMenu.h"
#include "app/editor/MainWindow.h"
#include "app/editor/ProjectController.h"
#include "app/editor/SimulationHost.h"
#include "app/editor/TimelineDock.h"
#include "io/HairFiles.h"
#include "widgets/Viewport.h"

#include <QDoubleSpinBox>
#include <QFile>
#include <QFileInfo>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QSlider>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>

#include <gtest/gtest.h>

using namespace wisp;
using namespace wisp::test;

namespace {

// Types `text` into a spin box as an artist does: select all, type, Enter.
void typeInto(QAbstractSpinBox* box, const QString& text)
{
    box->setFocus();
    QTest::keyClick(box, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(box, text);
    QTest::keyClick(box, Qt::Key_Return);
}

class TimelineTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        window = openEditor();
        // A light groom keeps the bake quick on two cores.
        doc()->editParameter(Param::Density, 2.0, false);
        doc()->undoStack()->clear();
        ASSERT_TRUE(waitForFrames(*window->simulation(), 3));
    }
    Document* doc() const { return window->document(); }
    TimelineDock* dock() const { return window->timelineDock(); }
    BakeController* bake() const { return dock()->bake(); }

    // Types the range into the dock and bakes it with a click; true when the bake finished.
    bool bakeFrames(int first, int last)
    {
        typeInto(dock()->lastFrameBox(), QString::number(last));
        typeInto(dock()->firstFrameBox(), QString::number(first));
        EXPECT_EQ(doc()->timeline().firstFrame, first);
        EXPECT_EQ(doc()->timeline().lastFrame, last);
        QSignalSpy finished(bake(), &BakeController::finished);
        QTest::mouseClick(dock()->bakeButton(), Qt::LeftButton);
        return waitUntil([&] { return finished.count() == 1; }, 6 * kWaitMs);
    }

    // The viewport draws frame `frame` of the cache, exactly.
    void expectDrawsBakedFrame(int frame)
    {
        const BakedFrame* baked = bake()->baked()->cache.find(frame);
        ASSERT_NE(baked, nullptr);
        const FramePtr drawn = window->viewport()->frame();
        ASSERT_TRUE(drawn);
        EXPECT_EQ(drawn->strands.offsets, bake()->baked()->cache.offsets);
        EXPECT_TRUE(drawn->strands.positions == baked->positions) << "frame " << frame << " is not as baked";
        // The head is drawn where the bake had it (a shake turns it), not at rest.
        EXPECT_TRUE(drawn->headToWorld == baked->headToWorld) << "frame " << frame << ": head not as baked";
    }

    std::unique_ptr<MainWindow> window;
};

} // namespace

TEST_F(TimelineTest, ABakedRangeScrubsToExactlyTheBakedPositions)
{
    // The head shakes, so every frame is another shape.
    HeadMotion shake;
    shake.setProcedural(motionPreset(MotionKind::Shake));
    ASSERT_EQ(doc()->setHeadMotion(shake, QStringLiteral("Shake")), QString());
    EXPECT_EQ(dock()->statusLabel()->text(), QStringLiteral("no bake"));

    ASSERT_TRUE(bakeFrames(1, 6));
    EXPECT_FALSE(window->simulation()->isPlaying()); // paused for the bake and under the cache
    const BakeCache& cache = bake()->baked()->cache;
    ASSERT_EQ(cache.frames.size(), 6u);
    EXPECT_EQ(bake()->framesDone(), 6);
    EXPECT_TRUE(dock()->statusLabel()->text().startsWith(QStringLiteral("cache: 6 frames, ")))
        << dock()->statusLabel()->text().toStdString();
    // After the bake the first frame is shown.
    EXPECT_TRUE(dock()->showingCache());
    expectDrawsBakedFrame(1);

    // Scrub with the slider's keys to frame 4.
    dock()->slider()->setFocus();
    for (int i = 0; i < 3; ++i)
        QTest::keyClick(dock()->slider(), Qt::Key_Right);
    ASSERT_EQ(dock()->currentFrame(), 4);
    EXPECT_EQ(dock()->frameLabel()->text(), QStringLiteral("frame 4"));
    expectDrawsBakedFrame(4);
    EXPECT_FALSE(cache.find(4)->positions == cache.find(1)->positions); // the head shook in between
    // The live simulation does not take the viewport back while the cache is shown.
    const std::uint64_t published = window->simulation()->publishedFrames();
    window->simulation()->stepOnce(); // a live step, published
    ASSERT_TRUE(waitForFramesSince(*window->simulation(), published, 1));
    QTest::qWait(20);
    expectDrawsBakedFrame(4);
    // End goes to the last frame.
    QTest::keyClick(dock()->slider(), Qt::Key_End);
    expectDrawsBakedFrame(6);

    // Playback reads the cache: a few frames on, each drawn as baked (looping 6 -> 1).
    QTest::mouseClick(dock()->playButton(), Qt::LeftButton);
    EXPECT_TRUE(dock()->isPlayingCache());
    QSignalSpy shown(dock(), &TimelineDock::cacheFrameShown);
    ASSERT_TRUE(waitUntil([&] { return shown.count() >= 3; }));
    QTest::mouseClick(dock()->playButton(), Qt::LeftButton);
    EXPECT_FALSE(dock()->isPlayingCache());
    EXPECT_GE(dock()->currentFrame(), 1);
    EXPECT_LE(dock()->currentFrame(), 4);
    expectDrawsBakedFrame(dock()->currentFrame());

    // Esc goes back to the live simulation.
    window->viewport()->setFocus();
    QTest::keyClick(window->viewport(), Qt::Key_Escape);
    EXPECT_FALSE(dock()->showingCache());
    EXPECT_EQ(window->viewport()->frame(), window->simulation()->latestFrame());
    EXPECT_EQ(dock()->frameLabel()->text(), QStringLiteral("live"));
    // Scrubbing shows the cache again; Play in the main toolbar leaves it and plays live.
    dock()->slider()->setFocus();
    QTest::keyClick(dock()->slider(), Qt::Key_Home);
    EXPECT_TRUE(dock()->showingCache());
    expectDrawsBakedFrame(1);
    window->playAction()->trigger();
    EXPECT_FALSE(dock()->showingCache());
    EXPECT_TRUE(window->simulation()->isPlaying());
}

TEST_F(TimelineTest, AnEditMarksTheCacheStaleNamedByItsUndoTextAndItStillScrubs)
{
    ASSERT_TRUE(bakeFrames(1, 3));
    EXPECT_FALSE(dock()->isStale());

    typeValue(window->forcePanel(), Param::WindSpeed, QStringLiteral("7"));
    ASSERT_DOUBLE_EQ(doc()->parameters().get(Param::WindSpeed), 7.0);
    EXPECT_TRUE(dock()->isStale());
    const QString edit = doc()->undoStack()->text(doc()->undoStack()->index() - 1);
    ASSERT_FALSE(edit.isEmpty());
    EXPECT_EQ(dock()->statusLabel()->text(), QStringLiteral("cache stale: %1 — bake again").arg(edit));

    // The stale cache still scrubs, labelled.
    dock()->slider()->setFocus();
    QTest::keyClick(dock()->slider(), Qt::Key_End);
    EXPECT_EQ(dock()->frameLabel()->text(), QStringLiteral("frame 3 (stale)"));
    expectDrawsBakedFrame(3);

    // A new bake is fresh again; a change of the range makes it stale too.
    ASSERT_TRUE(bakeFrames(1, 3));
    EXPECT_FALSE(dock()->isStale());
    typeInto(dock()->lastFrameBox(), QStringLiteral("5"));
    EXPECT_TRUE(dock()->isStale());
    EXPECT_TRUE(dock()->statusLabel()->text().contains(QStringLiteral("frames 1–5")))
        << dock()->statusLabel()->text().toStdString();
}

TEST_F(TimelineTest, CancelStopsABakeWithinAFrameAndKeepsNoHalfCache)
{
    typeInto(dock()->lastFrameBox(), QStringLiteral("400"));
    QSignalSpy cancelled(bake(), &BakeController::cancelled);
    QTest::mouseClick(dock()->bakeButton(), Qt::LeftButton);
    EXPECT_TRUE(bake()->isRunning());
    EXPECT_FALSE(dock()->bakeButton()->isEnabled());
    ASSERT_TRUE(dock()->cancelButton()->isEnabled());
    // The window keeps handling events while it bakes: the progress bar moves.
    ASSERT_TRUE(waitUntil([&] { return bake()->framesDone() >= 2; }, 6 * kWaitMs));
    EXPECT_EQ(dock()->progressBar()->value(), bake()->framesDone());
    const int atClick = bake()->framesDone();
    QTest::mouseClick(dock()->cancelButton(), Qt::LeftButton);
    ASSERT_TRUE(waitUntil([&] { return cancelled.count() == 1; }));
    EXPECT_FALSE(bake()->isRunning());
    // The worker stops at its next step: at most the frame it was in ends after the click.
    // (Progress reports already queued when the click came may still raise framesDone.)
    EXPECT_GE(bake()->framesDone(), atClick);
    EXPECT_LE(bake()->framesFinishedAfterCancel(), 1);
    EXPECT_LT(bake()->framesDone(), 400);
    EXPECT_EQ(bake()->baked(), nullptr);
    EXPECT_EQ(dock()->statusLabel()->text(), QStringLiteral("no bake"));
    EXPECT_TRUE(dock()->bakeButton()->isEnabled());
}

TEST_F(TimelineTest, TheMemoryBoundsRefusalShowsInTheDock)
{
    bake()->setMemoryBoundBytes(4096); // not one frame of this groom
    typeInto(dock()->lastFrameBox(), QStringLiteral("10"));
    QSignalSpy failed(bake(), &BakeController::failed);
    QTest::mouseClick(dock()->bakeButton(), Qt::LeftButton);
    ASSERT_TRUE(waitUntil([&] { return failed.count() == 1; }, 3 * kWaitMs));
    EXPECT_EQ(bake()->baked(), nullptr);
    const QString status = dock()->statusLabel()->text();
    EXPECT_TRUE(status.startsWith(QStringLiteral("bake refused: a bake of 10 frames"))) << status.toStdString();
    EXPECT_TRUE(status.contains(QStringLiteral("memory bound"))) << status.toStdString();
}

TEST_F(TimelineTest, SaveAndReopenKeepTheRange)
{
    window->fileMenu()->setInteractive(false);
    typeInto(dock()->lastFrameBox(), QStringLiteral("12"));
    typeInto(dock()->firstFrameBox(), QStringLiteral("3"));
    typeInto(dock()->fpsBox(), QStringLiteral("30"));
    EXPECT_EQ(doc()->timeline(), (BakeRange{ 3, 12, 30.0 }));
    // Each is one undo step.
    EXPECT_EQ(doc()->undoStack()->count(), 3);
    // A range that ends before it starts is refused; the box shows the document's again.
    typeInto(dock()->firstFrameBox(), QStringLiteral("20"));
    EXPECT_EQ(doc()->timeline().firstFrame, 3);
    EXPECT_EQ(dock()->firstFrameBox()->value(), 3);

    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString path = dir.filePath(QStringLiteral("range.wisp"));
    ProjectController* projects = window->fileMenu()->projects();
    ASSERT_TRUE(projects->saveAs(path)) << projects->lastError().toStdString();
    ASSERT_TRUE(projects->newProject()); // saved, so nothing is asked
    EXPECT_EQ(doc()->timeline(), BakeRange{});
    EXPECT_EQ(dock()->lastFrameBox()->value(), BakeRange{}.lastFrame);
    ASSERT_TRUE(projects->open(path)) << projects->lastError().toStdString();
    EXPECT_EQ(doc()->timeline(), (BakeRange{ 3, 12, 30.0 }));
    EXPECT_EQ(dock()->firstFrameBox()->value(), 3);
    EXPECT_EQ(dock()->lastFrameBox()->value(), 12);
    EXPECT_DOUBLE_EQ(dock()->fpsBox()->value(), 30.0);
}

TEST_F(TimelineTest, TheBakeExportsAsAHairSequenceOfTheBakedFramesAndAsUsda)
{
    ASSERT_TRUE(bakeFrames(2, 4));
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    // Without # a .hair sequence has no place for the frame number: refused, nothing written.
    const QString noPattern = dir.filePath(QStringLiteral("hair.hair"));
    EXPECT_TRUE(dock()->exportBake(noPattern).contains(QStringLiteral("needs # in the file name")));
    EXPECT_FALSE(QFileInfo::exists(noPattern));

    ASSERT_EQ(dock()->exportBake(dir.filePath(QStringLiteral("hair.####.hair"))), QString());
    const BakeCache& cache = bake()->baked()->cache;
    for (int frame = 2; frame <= 4; ++frame) {
        const QString path = dir.filePath(QStringLiteral("hair.%1.hair").arg(frame, 4, 10, QLatin1Char('0')));
        const io::Result<io::HairReadResult> read = io::readHair(path.toStdString());
        ASSERT_TRUE(read) << read.error().toString();
        EXPECT_EQ(read.value().strands.offsets, cache.offsets);
        EXPECT_TRUE(read.value().strands.positions == cache.find(frame)->positions) << "frame " << frame;
    }
    EXPECT_FALSE(QFileInfo::exists(dir.filePath(QStringLiteral("hair.0001.hair")))); // not in the range

    const QString usda = dir.filePath(QStringLiteral("bake.usda"));
    ASSERT_EQ(dock()->exportBake(usda), QString());
    QFile file(usda);
    ASSERT_TRUE(file.open(QIODevice::ReadOnly));
    const QByteArray text = file.readAll();
    EXPECT_TRUE(text.contains("timeCodesPerSecond = 24"));
    EXPECT_TRUE(text.contains("startTimeCode = 2\n") && text.contains("endTimeCode = 4\n"));
    EXPECT_TRUE(
        text.contains("            2: [") && text.contains("            4: [") && !text.contains("            1: ["))
        << "points sampled at frames 2..4";
    EXPECT_EQ(dock()->exportBake(dir.filePath(QStringLiteral("bake.abc"))).contains(QStringLiteral(".usda")), true);
}
