#pragma once
// What several GUI tests need: waiting for the simulation host's frames, measuring where the hair
// hangs, and typing into a parameter panel as an artist does.

#include "app/editor/FileMenu.h"
#include "app/editor/MainWindow.h"
#include "app/editor/SimulationHost.h"
#include "sim/solver/Frame.h"
#include "widgets/ParameterPanel.h"

#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QStandardPaths>
#include <QTest>

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <memory>

namespace wisp::test {

// Default waits: generous for a Release build on a busy two-core machine, and longer still in the
// sanitizer build, which runs several times slower (WISP_SLOW_BUILD_FACTOR, tests/CMakeLists.txt).
constexpr int kWaitMs = 10000 * WISP_SLOW_BUILD_FACTOR;
// Generous bounds for waits that only catch a hang, such as a whole groom and drape (the sanitizer
// build is ~10x slower, and on a loaded two-core machine the editor's first groom and drape there
// took over kWaitMs).
inline constexpr int kSceneWaitMs = 120000 * WISP_SLOW_BUILD_FACTOR;

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
