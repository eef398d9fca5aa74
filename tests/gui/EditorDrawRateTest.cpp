// The editor's viewport while it simulates, as an artist first sees it: the default head and groom
// in the default window, the solver on the same cores. Counts paints against the frames the
// simulation published and prints the rate (never asserted: machines are shared). This is the
// figure issue 14's bar is about ("the default scene while simulating, in the editor's default
// window"); ViewportTest.DrawRate* feed prepared frames to the view alone.
#include "GuiTestSupport.h"

#include "app/editor/MainWindow.h"
#include "app/editor/SimulationHost.h"
#include "widgets/Viewport.h"

#include <QElapsedTimer>
#include <QStandardPaths>
#include <QTest>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace wisp;
using namespace wisp::test;

TEST(EditorDrawRate, WhileSimulatingEachPaintShowsANewFrame)
{
    QStandardPaths::setTestModeEnabled(true); // the default window, not the artist's
    const std::unique_ptr<MainWindow> window = newEditorWindow();
    window->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(window.get()));
    SimulationHost& host = *window->simulation();
    ASSERT_TRUE(host.isPlaying());
    ASSERT_TRUE(waitForFrames(host, 30, kSceneWaitMs)); // groomed, draped and moving
    Viewport& viewport = *window->viewport();
    // Paints counted as they come, each one's share of the strands and whether it was a preview.
    const int paints
        = qEnvironmentVariableIntValue("WISP_RATE_PAINTS") > 0 ? qEnvironmentVariableIntValue("WISP_RATE_PAINTS") : 60;
    const std::uint64_t firstPaint = viewport.paintCount();
    const std::uint64_t firstFrame = host.publishedFrames();
    double fractionSum = 0.0;
    double paintMsSum = 0.0;
    int looks = 0;
    int halfResolution = 0;
    std::uint64_t seen = firstPaint;
    QElapsedTimer clock;
    clock.start();
    while (viewport.paintCount() < firstPaint + static_cast<std::uint64_t>(paints) && clock.elapsed() < kSceneWaitMs) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 5);
        if (viewport.paintCount() != seen) {
            seen = viewport.paintCount();
            fractionSum += viewport.lastDrawnFraction();
            paintMsSum += viewport.lastPaintMilliseconds();
            halfResolution += viewport.lastPaintHairAtHalfResolution() ? 1 : 0;
            ++looks;
        }
    }
    const double seconds = static_cast<double>(clock.nsecsElapsed()) * 1e-9;
    const std::uint64_t painted = viewport.paintCount() - firstPaint;
    const std::uint64_t published = host.publishedFrames() - firstFrame;
    ASSERT_GE(painted, static_cast<std::uint64_t>(paints));
    ASSERT_GT(looks, 0);
    std::printf("[ editor ] simulating, %dx%d viewport of a %dx%d window, %s: %.1f fps, %.0f%% strands, %.1f ms GL "
                "a paint, %d of %d paints looked at were at half resolution; %llu paints for %llu frames published\n",
        viewport.width(), viewport.height(), window->width(), window->height(),
        viewport.softwareRenderer() ? "software GL" : "hardware GL", static_cast<double>(painted) / seconds,
        100.0 * fractionSum / looks, paintMsSum / looks, halfResolution, looks,
        static_cast<unsigned long long>(painted), static_cast<unsigned long long>(published));
    RecordProperty("fps_editor_simulating", static_cast<int>(std::lround(static_cast<double>(painted) / seconds)));
    // A paint shows a frame: a view that painted more often than frames came would be painting the
    // same hair again (a refinement paint after a pause in the frames is the only other kind).
    EXPECT_LE(painted, published + published / 4 + 2);
    EXPECT_GT(fractionSum / looks, 0.0);
}
