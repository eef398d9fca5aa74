#pragma once
// What several GUI tests need: waiting for the simulation host's frames, measuring where the hair
// hangs, and typing into a parameter panel as an artist does.

#include "app/editor/Document.h"
#include "app/editor/FileMenu.h"
#include "app/editor/MainWindow.h"
#include "app/editor/SimulationHost.h"
#include "sim/solver/Frame.h"
#include "widgets/ParameterPanel.h"

#include <QAction>
#include <QApplication>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QMenu>
#include <QMenuBar>
#include <QMouseEvent>
#include <QSignalSpy>
#include <QSlider>
#include <QStandardPaths>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QTest>
#include <QUndoStack>

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace wisp::test {

// Default waits: generous for a Release build on a busy two-core machine, and longer still in the
// sanitizer build, which runs several times slower (WISP_SLOW_BUILD_FACTOR, tests/CMakeLists.txt).
constexpr int kWaitMs = 10000 * WISP_SLOW_BUILD_FACTOR;
// Generous bounds for waits that only catch a hang, such as a whole groom and drape (the sanitizer
// build is ~10x slower, and on a loaded two-core machine the editor's first groom and drape there
// took over kWaitMs).
inline constexpr int kSceneWaitMs = 120000 * WISP_SLOW_BUILD_FACTOR;

// How long a call that must return (closing the editor, destroying the simulation host) may block
// before it counts as hung: far above anything a healthy one takes however loaded the machine.
constexpr int kHangGuardMs = 30000 * WISP_SLOW_BUILD_FACTOR;

// Runs `call` on this thread (a QObject is destroyed on its own thread) while a watchdog thread waits
// for it to return, at most timeoutMs. Should it never return, the watchdog names the hang on
// stderr and aborts the run, so CI reports "HANG: <what>" at once instead of a 600 s timeout. No
// duration is measured or asserted: the call returned, or it hung. The watchdog is joined before
// this returns, so thread counts taken afterwards do not see it.
inline void runWithHangGuard(const char* what, const std::function<void()>& call, int timeoutMs = kHangGuardMs)
{
    std::mutex mutex;
    std::condition_variable returned;
    bool done = false;
    std::thread watchdog([&] {
        std::unique_lock lock(mutex);
        if (!returned.wait_for(lock, std::chrono::milliseconds(timeoutMs), [&] { return done; })) {
            std::fprintf(stderr, "HANG: %s did not return (hang guard %d ms)\n", what, timeoutMs);
            std::fflush(stderr);
            std::abort();
        }
    });
    call();
    {
        std::lock_guard lock(mutex);
        done = true;
    }
    returned.notify_one();
    watchdog.join();
}

// Polls `done` while the event loop runs, up to timeoutMs; its last answer.
inline bool waitUntil(const std::function<bool()>& done, int timeoutMs = kWaitMs)
{
    QElapsedTimer timer;
    timer.start();
    while (!done() && timer.elapsed() < timeoutMs)
        QTest::qWait(5);
    return done();
}

// Waits for `count` frames published after `since` (a publishedFrames() taken before the request:
// a paused step is published within microseconds, maybe before the wait starts).
inline bool waitForFramesSince(
    const SimulationHost& host, std::uint64_t since, std::uint64_t count, int timeoutMs = kWaitMs)
{
    return waitUntil([&] { return host.publishedFrames() >= since + count; }, timeoutMs);
}

// Waits for a new window's host to publish its first frame: the first groom and drape have run.
inline bool waitForFirstFrame(const SimulationHost& host)
{
    return waitUntil([&] { return host.latestFrame() != nullptr; }, kSceneWaitMs);
}

// Waits for `count` more frames of a playing host.
inline bool waitForFrames(const SimulationHost& host, std::uint64_t count, int timeoutMs = kWaitMs)
{
    return waitForFramesSince(host, host.publishedFrames(), count, timeoutMs);
}

// A new editor window whose recovery question, should a test process killed earlier have left an
// autosave, is answered Later instead of opening a modal box that nobody would close (show()
// asks it). The work stays for the tests that look at recovery.
inline std::unique_ptr<MainWindow> newEditorWindow()
{
    auto window = std::make_unique<MainWindow>();
    window->fileMenu()->setRecoveryPrompt([](const QString&) { return FileMenu::RecoveryAnswer::Later; });
    return window;
}

// The editor's main window as an artist starts it (settings and data in Qt's test locations), shown
// at `width` x `height`, exposed and active, so key and mouse events reach it.
inline std::unique_ptr<MainWindow> openEditor(int width = 1300, int height = 850)
{
    QStandardPaths::setTestModeEnabled(true);
    auto window = newEditorWindow();
    window->resize(width, height);
    window->show();
    EXPECT_TRUE(QTest::qWaitForWindowExposed(window.get()));
    window->activateWindow();
    EXPECT_TRUE(QTest::qWaitForWindowActive(window.get()));
    return window;
}

// The window's menu titled `title` (its mnemonic's & left out: "Help"), or null.
inline QMenu* menuNamed(const MainWindow& window, const QString& title)
{
    for (QAction* top : window.menuBar()->actions())
        if (top->menu() && top->menu()->title().remove('&') == title)
            return top->menu();
    return nullptr;
}

// Waits until the host has taken every edit: no regroom finished (sceneReady) for `quietMs`.
inline void waitUntilRegroomsStop(SimulationHost& host, int quietMs)
{
    QSignalSpy ready(&host, &SimulationHost::sceneReady);
    while (ready.wait(quietMs)) { }
}

// The editor as the painting and styling tests start it: open, on a light groom (2 strands/cm² keeps
// regrooms and the real-time simulation quick on two cores) with `edits` made too, the undo
// history cleared, paused with a first frame, every regroom taken (quiet for `quietMs`). A failure
// is recorded (the caller checks HasFailure()) when it does not get there.
inline std::unique_ptr<MainWindow> openLightPausedEditor(
    const std::function<void(Document&)>& edits = {}, int quietMs = 600 * WISP_SLOW_BUILD_FACTOR)
{
    auto window = openEditor();
    Document* doc = window->document();
    doc->editRegionParameter(0, Param::Density, 2.0, false);
    if (edits)
        edits(*doc);
    doc->undoStack()->clear();
    // Paused: strands that are carried over keep exactly their state, so frames compare exactly.
    window->simulation()->pause();
    EXPECT_TRUE(waitForFirstFrame(*window->simulation())) << "no first frame within " << kSceneWaitMs << " ms";
    waitUntilRegroomsStop(*window->simulation(), quietMs);
    return window;
}

// Mean root and tip of a frame's strands, metres.
struct Ends {
    glm::vec3 tip{ 0.0f };
    glm::vec3 root{ 0.0f };
};

inline Ends meanEnds(const FramePtr& frame)
{
    Ends e;
    const HairCurves& c = frame->strands;
    for (std::size_t s = 0; s < c.strandCount(); ++s) {
        e.root += c.strand(s).front();
        e.tip += c.strand(s).back();
    }
    e.root /= static_cast<float>(c.strandCount());
    e.tip /= static_cast<float>(c.strandCount());
    return e;
}

// Presses the slider's handle where the style draws it, moves right `steps` times by `stepPx`
// (each move a live edit), releases: real mouse events.
inline void dragSliderHandle(QSlider* slider, int steps, int stepPx)
{
    QStyleOptionSlider option;
    option.initFrom(slider);
    option.orientation = slider->orientation();
    option.minimum = slider->minimum();
    option.maximum = slider->maximum();
    option.sliderPosition = slider->sliderPosition();
    option.sliderValue = slider->value();
    const QRect handle = slider->style()->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderHandle, slider);
    QPoint at = handle.center();
    QTest::mousePress(slider, Qt::LeftButton, Qt::NoModifier, at);
    for (int i = 0; i < steps; ++i) {
        at += QPoint(stepPx, 0);
        QMouseEvent move(QEvent::MouseMove, at, slider->mapToGlobal(at), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(slider, &move);
    }
    QTest::mouseRelease(slider, Qt::LeftButton, Qt::NoModifier, at);
}

// Types a value into a parameter's spin box: select all, type, Enter.
inline void typeValue(ParameterPanel* panel, Param id, const QString& text)
{
    QDoubleSpinBox* spin = panel->spinBoxFor(id);
    ASSERT_NE(spin, nullptr);
    spin->setFocus();
    QTest::keyClick(spin, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(spin, text);
    QTest::keyClick(spin, Qt::Key_Return);
}

} // namespace wisp::test
