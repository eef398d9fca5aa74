#pragma once
// What the simulation host's GUI tests share (SimulationHostTest.cpp, SimulationHostControlTest.cpp,
// SimulationHostPacerTest.cpp): light parameters, whole-frame checks, thread counts, a test clock
// the test moves, and the SimulationHostTest fixture (a host that grooms the default head).

#include "../sim/SimFixtures.h"
#include "GuiTestSupport.h"
#include "app/editor/SimulationHost.h"
#include "app/editor/SimulationHostPacer.h"
#include "sim/geometry/DefaultHead.h"
#include "sim/solver/SolverSettings.h"

#include <QSignalSpy>
#include <QTest>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace wisp::test {

// A lighter groom keeps the real-time simulation quick on two cores; no wind so that tips settle.
inline ParameterValues lightValues()
{
    ParameterValues v;
    v.set(Param::Density, 2.0);
    v.set(Param::WindSpeed, 0.0);
    v.set(Param::Turbulence, 0.0);
    return v;
}

inline ParameterValues with(ParameterValues v, std::initializer_list<std::pair<Param, double>> changes)
{
    for (const auto& [id, value] : changes)
        EXPECT_EQ(v.set(id, value), "");
    return v;
}

// Whole and self-consistent: what a reader of any published frame may rely on.
inline ::testing::AssertionResult isWhole(const FramePtr& frame)
{
    if (!frame)
        return ::testing::AssertionFailure() << "no frame";
    const HairCurves& c = frame->strands;
    if (c.offsets.empty() || c.offsets.front() != 0)
        return ::testing::AssertionFailure() << "offsets do not start at 0";
    if (c.offsets.back() != c.positions.size())
        return ::testing::AssertionFailure()
            << "offsets end at " << c.offsets.back() << " for " << c.positions.size() << " positions";
    for (std::size_t i = 1; i < c.offsets.size(); ++i)
        if (c.offsets[i] < c.offsets[i - 1] + 2)
            return ::testing::AssertionFailure() << "strand " << i - 1 << " has fewer than 2 points";
    for (const glm::vec3& p : c.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return ::testing::AssertionFailure() << "a position is not finite";
    return ::testing::AssertionSuccess();
}

inline long threadCount()
{
    return static_cast<long>(
        std::distance(std::filesystem::directory_iterator("/proc/self/task"), std::filesystem::directory_iterator()));
}

// Whether this process's thread count falls to at most `most` within timeoutMs. A joined thread
// has left its code, but the kernel may list it in /proc/self/task a little longer while it
// finishes exiting (3 to 13 ms after pthread_join returned, on a 2-vCPU VM: a test that counted at
// once failed one run in four); a thread that was never joined stays, and fails.
inline bool threadCountFallsTo(long most, int timeoutMs = kWaitMs)
{
    return waitUntil([&] { return threadCount() <= most; }, timeoutMs);
}

// The pacer's clock, moved by the test (SimulationHost::SecondsClock). Each read returns the time
// and then adds perRead: a paced step reads it at its start, after the solver and after building
// its frame, so perRead sets what every step costs in the host's eyes, whatever the machine does.
// hold() makes the next read wait until release(): the simulation thread is then stuck mid-work,
// which shows that a GUI-thread call returns without waiting for it.
class TestClock {
public:
    double read()
    {
        std::unique_lock lock(m_mutex);
        if (m_holding) {
            m_held = true;
            m_changed.notify_all();
            m_changed.wait(lock, [&] { return !m_holding; });
            m_held = false;
        }
        const double t = m_seconds;
        m_seconds += m_perRead;
        return t;
    }
    void advance(double seconds)
    {
        std::lock_guard lock(m_mutex);
        m_seconds += seconds;
    }
    void setPerRead(double seconds)
    {
        std::lock_guard lock(m_mutex);
        m_perRead = seconds;
    }
    void hold()
    {
        std::lock_guard lock(m_mutex);
        m_holding = true;
    }
    // Thread: GUI. True once the simulation thread waits in read(); bounded by a hang guard only.
    bool waitUntilHeld()
    {
        std::unique_lock lock(m_mutex);
        return m_changed.wait_for(lock, std::chrono::seconds(30 * WISP_SLOW_BUILD_FACTOR), [&] { return m_held; });
    }
    bool isHeld()
    {
        std::lock_guard lock(m_mutex);
        return m_held;
    }
    void release()
    {
        {
            std::lock_guard lock(m_mutex);
            m_holding = false;
        }
        m_changed.notify_all();
    }

private:
    std::mutex m_mutex;
    std::condition_variable m_changed;
    double m_seconds = 0.0;
    double m_perRead = 0.0;
    bool m_holding = false;
    bool m_held = false;
};

// Releases a held clock when a test leaves early, so that the host's destructor can join.
struct ReleaseOnExit {
    TestClock& clock;
    ~ReleaseOnExit() { clock.release(); }
};

class SimulationHostTest : public ::testing::Test {
protected:
    void SetUp() override { host = std::make_unique<SimulationHost>(); }

    // Replaces the host by one paced by `clock` (which then outlives it).
    void useTestClock()
    {
        clock = std::make_shared<TestClock>();
        host.reset();
        host = std::make_unique<SimulationHost>([c = clock] { return c->read(); });
    }

    // Grooms the default head on the simulation thread and waits for its step-0 frame.
    ::testing::AssertionResult startScene(const ParameterValues& values)
    {
        QSignalSpy ready(host.get(), &SimulationHost::sceneReady);
        QSignalSpy refused(host.get(), &SimulationHost::errorOccurred);
        host->setScene(defaultHead().mesh, defaultHead().growthWeights, values);
        if (!waitUntil([&] { return ready.count() > 0 || refused.count() > 0; }, kSceneWaitMs))
            return ::testing::AssertionFailure() << "no sceneReady within " << kSceneWaitMs << " ms";
        if (refused.count() > 0)
            return ::testing::AssertionFailure() << refused.front().front().toString().toStdString();
        return ::testing::AssertionSuccess();
    }

    // A new host (the fixture's own let go first) playing the light scene, `frames` frames in: what
    // the destroy tests take apart. Its own thread is running by then.
    ::testing::AssertionResult playNewHost(std::uint64_t frames)
    {
        host.reset();
        host = std::make_unique<SimulationHost>();
        if (::testing::AssertionResult started = startScene(lightValues()); !started)
            return started;
        host->play();
        if (!waitForFrames(*host, frames))
            return ::testing::AssertionFailure() << "fewer than " << frames << " frames while playing";
        return ::testing::AssertionSuccess();
    }

    // Lets the hair move for `frames` published frames, then averages the ends over a few more
    // (turbulence is off, but a settling strand still sways a little).
    Ends settledEnds(int frames = 90)
    {
        EXPECT_TRUE(waitForFrames(*host, static_cast<std::uint64_t>(frames)));
        Ends sum;
        for (int i = 0; i < 5; ++i) {
            EXPECT_TRUE(waitForFrames(*host, 2));
            const Ends e = meanEnds(host->latestFrame());
            sum.tip += e.tip / 5.0f;
            sum.root += e.root / 5.0f;
        }
        return sum;
    }

    std::shared_ptr<TestClock> clock; // before host: destroyed after it
    std::unique_ptr<SimulationHost> host;
};

} // namespace wisp::test
