// The simulation host as the editor drives it: requests from the GUI thread, frames back from the
// simulation thread. The checks are on published frames only (where the tips are, what the counters
// say), not on the solver, and the GUI thread's event loop runs through QTest::qWait / QSignalSpy.
// The pacing policy is also tested on its own, with made-up timings, in SimulationHostPacer tests.
#include "app/editor/SimulationHost.h"
#include "GuiTestSupport.h"
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
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

using namespace wisp;
using namespace wisp::test;

namespace {

const DefaultHead& defaultHead()
{
    static const DefaultHead head = makeDefaultHead();
    return head;
}

// A lighter groom keeps the real-time simulation quick on two cores; no wind so that tips settle.
ParameterValues lightValues()
{
    ParameterValues v;
    v.set(Param::Density, 2.0);
    v.set(Param::WindSpeed, 0.0);
    v.set(Param::Turbulence, 0.0);
    return v;
}

ParameterValues with(ParameterValues v, std::initializer_list<std::pair<Param, double>> changes)
{
    for (const auto& [id, value] : changes)
        EXPECT_EQ(v.set(id, value), "");
    return v;
}

// Whole and self-consistent: what a reader of any published frame may rely on.
::testing::AssertionResult isWhole(const FramePtr& frame)
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

long threadCount()
{
    return static_cast<long>(
        std::distance(std::filesystem::directory_iterator("/proc/self/task"), std::filesystem::directory_iterator()));
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

// Generous bounds for waits that only catch a hang (the sanitizer build is ~10x slower).
constexpr int kSceneWaitMs = 120000 * WISP_SLOW_BUILD_FACTOR;

double processCpuSeconds()
{
    return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

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

} // namespace

TEST_F(SimulationHostTest, PublishesARestFrameAfterSetSceneAndFramesOncePlaying)
{
    EXPECT_EQ(host->latestFrame(), nullptr);
    EXPECT_GE(host->solverThreadCount(), 1);
    EXPECT_EQ(host->solverThreadCount(), std::max(1, static_cast<int>(std::thread::hardware_concurrency()) - 1));
    QSignalSpy frames(host.get(), &SimulationHost::frameReady);
    QSignalSpy playing(host.get(), &SimulationHost::playingChanged);
    ASSERT_TRUE(startScene(lightValues()));

    const FramePtr rest = host->latestFrame();
    ASSERT_TRUE(isWhole(rest));
    EXPECT_EQ(rest->step, 0u);
    EXPECT_EQ(rest->groomVersion, 1u);
    EXPECT_EQ(rest->simulatedSeconds, 0.0);
    EXPECT_GT(rest->strands.strandCount(), 100u);
    EXPECT_GT(rest->simulatedStrands, 0u);
    EXPECT_LT(rest->simulatedStrands, rest->strands.strandCount()); // keys only, by default
    EXPECT_GT(rest->simulatedParticles, rest->simulatedStrands);
    EXPECT_FALSE(host->isPlaying());
    EXPECT_EQ(host->effectiveSubsteps(), lightValues().getInt(Param::Substeps));

    host->play();
    EXPECT_TRUE(host->isPlaying());
    ASSERT_EQ(playing.count(), 1);
    EXPECT_TRUE(playing.front().front().toBool());
    host->play(); // already playing: no second signal
    EXPECT_EQ(playing.count(), 1);

    ASSERT_TRUE(waitForFrames(*host, 30));
    const FramePtr frame = host->latestFrame();
    ASSERT_TRUE(isWhole(frame));
    EXPECT_GE(frame->step, 30u);
    EXPECT_EQ(frame->groomVersion, 1u);
    EXPECT_NEAR(frame->simulatedSeconds, static_cast<double>(frame->step) / 60.0, 1e-6);
    EXPECT_GT(frame->stepMilliseconds, 0.0);
    EXPECT_EQ(frame->strands.offsets, rest->strands.offsets);
    EXPECT_GT(frames.count(), 0);
    // Coalesced: never more signals than frames.
    EXPECT_LE(static_cast<std::uint64_t>(frames.count()), host->publishedFrames());
}

TEST_F(SimulationHostTest, KeepsRealTimeWithoutRunningAhead)
{
    // One step per time step of the pacer's clock, counted: a clock that stands still gets no more
    // steps than the one due at once, and each time step it moves on buys exactly one more.
    useTestClock();
    ASSERT_TRUE(startScene(lightValues()));
    const double timeStep = solverSettingsFrom(lightValues()).timeStepSeconds; // a float, as the solver has it
    const std::uint64_t groomed = host->publishedFrames();
    host->play();
    ASSERT_TRUE(waitUntil([&] { return host->latestFrame()->step >= 1; }));
    QTest::qWait(100); // time for the simulation thread to run ahead, would it
    EXPECT_EQ(host->latestFrame()->step, 1u);
    for (std::uint64_t expected = 2; expected <= 6; ++expected) {
        clock->advance(timeStep);
        ASSERT_TRUE(waitUntil([&] { return host->latestFrame()->step >= expected; }));
        QTest::qWait(20);
        EXPECT_EQ(host->latestFrame()->step, expected);
    }
    EXPECT_EQ(host->publishedFrames(), groomed + 6);
    const FramePtr last = host->latestFrame();
    EXPECT_NEAR(last->simulatedSeconds, 6.0 * timeStep, 1e-9);
    EXPECT_FALSE(last->fallingBehind) << "steps that cost nothing keep real time";
    EXPECT_EQ(last->timeScale, 1.0);
}

TEST_F(SimulationHostTest, HeavierGravityThroughSetParametersLowersTheTipsWithoutRegrooming)
{
    // Stiff enough hair to hold some of its shape (at the default stiffness the weight of the hair
    // below each joint already hangs it almost straight down at 9.81 m/s²).
    ASSERT_TRUE(startScene(with(lightValues(), { { Param::Stiffness, 0.6 } })));
    host->play();
    const float lightTip = settledEnds().tip.y;

    host->setParameters(with(lightValues(), { { Param::Stiffness, 0.6 }, { Param::Gravity, 20.0 } }));
    EXPECT_TRUE(host->isPlaying());
    const float heavyTip = settledEnds().tip.y;
    EXPECT_LT(heavyTip, lightTip - 0.003f);
    EXPECT_EQ(host->latestFrame()->groomVersion, 1u); // forces only: same groom, same strands
}

TEST_F(SimulationHostTest, NegativeGravityFloatsTheTipsAboveTheRoots)
{
    ASSERT_TRUE(startScene(lightValues()));
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 5));
    host->setParameters(with(lightValues(), { { Param::Gravity, -2.8 }, { Param::Stiffness, 0.02 } }));
    const Ends floating = settledEnds(120);
    EXPECT_GT(floating.tip.y, floating.root.y + 0.05f);
}

TEST_F(SimulationHostTest, WindTowardPlusXMovesTheTipsTowardPlusX)
{
    ASSERT_TRUE(startScene(lightValues()));
    host->play();
    const float calmX = settledEnds().tip.x;
    const ParameterValues windy = with(lightValues(), { { Param::WindSpeed, 10.0 }, { Param::WindAzimuth, 0.0 } });
    host->setParameters(windy);
    const float windyX = settledEnds().tip.x;
    EXPECT_GT(windyX, calmX + 0.01f);
    const glm::vec3 wind = host->latestFrame()->wind; // for the viewport's arrow
    EXPECT_NEAR(wind.x, solverSettingsFrom(windy).wind.x, 1e-5f);
    EXPECT_NEAR(wind.x, 10.0f, 1e-4f);
}

TEST_F(SimulationHostTest, OnlyTheNewestParametersMatter)
{
    ASSERT_TRUE(startScene(lightValues()));
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 3));
    for (int i = 1; i <= 200; ++i) // a slider dragged faster than the solver steps
        host->setParameters(with(lightValues(), { { Param::WindSpeed, 0.1 * i }, { Param::WindAzimuth, 0.0 } }));
    ASSERT_TRUE(waitForFrames(*host, 3));
    EXPECT_NEAR(host->latestFrame()->wind.x, 20.0f, 1e-3f);
}

TEST_F(SimulationHostTest, GuiThreadCallsReturnWhileTheSimulationThreadIsStuck)
{
    // Instead of timing the calls: the simulation thread is held inside a read of the pacer's
    // clock, and every request still returns (were one to wait for the solver, this test would hang).
    useTestClock();
    ASSERT_TRUE(startScene(lightValues()));
    host->play();
    ASSERT_TRUE(waitUntil([&] { return host->latestFrame()->step >= 1; }));
    QSignalSpy ready(host.get(), &SimulationHost::sceneReady);
    {
        const ReleaseOnExit releaseOnExit{ *clock };
        clock->hold();
        ASSERT_TRUE(clock->waitUntilHeld());
        for (int i = 1; i <= 200; ++i)
            host->setParameters(with(lightValues(), { { Param::WindSpeed, 0.1 * i }, { Param::WindAzimuth, 0.0 } }));
        host->setParameters(
            with(lightValues(), { { Param::WindSpeed, 20.0 }, { Param::WindAzimuth, 0.0 }, { Param::Segments, 7.0 } }));
        host->pause();
        host->stepOnce();
        EXPECT_TRUE(clock->isHeld()) << "the simulation thread moved on: the calls may have waited for it";
        EXPECT_EQ(ready.count(), 0);
    }
    // Released: the newest parameters (a regroom) and the step follow.
    ASSERT_TRUE(waitUntil([&] { return ready.count() > 0; }, kSceneWaitMs));
    ASSERT_TRUE(waitUntil([&] { return host->latestFrame()->groomVersion == 2; }));
    EXPECT_EQ(host->latestFrame()->strands.pointsIn(0), 8u);
    EXPECT_NEAR(host->latestFrame()->wind.x, 20.0f, 1e-3f);
    EXPECT_FALSE(host->isPlaying());
}

TEST_F(SimulationHostTest, PauseStopsFramesAndStepOnceAddsExactlyOne)
{
    QSignalSpy playing(host.get(), &SimulationHost::playingChanged);
    ASSERT_TRUE(startScene(lightValues()));
    const std::uint64_t groomed = host->publishedFrames();
    host->stepOnce(); // paused from the start: one step
    ASSERT_TRUE(waitForFramesSince(*host, groomed, 1));
    EXPECT_EQ(host->latestFrame()->step, 1u);

    host->play();
    ASSERT_TRUE(waitForFrames(*host, 10));
    host->stepOnce(); // ignored while playing
    host->pause();
    EXPECT_FALSE(host->isPlaying());
    ASSERT_EQ(playing.count(), 2);
    EXPECT_FALSE(playing.at(1).front().toBool());
    QTest::qWait(50); // a step that was running when pause() came still lands
    const std::uint64_t paused = host->publishedFrames();
    const std::uint64_t step = host->latestFrame()->step;
    QTest::qWait(300);
    EXPECT_EQ(host->publishedFrames(), paused);

    host->stepOnce();
    ASSERT_TRUE(waitForFramesSince(*host, paused, 1));
    QTest::qWait(200);
    EXPECT_EQ(host->publishedFrames(), paused + 1);
    EXPECT_EQ(host->latestFrame()->step, step + 1);
    EXPECT_NEAR(host->latestFrame()->simulatedSeconds, static_cast<double>(step + 1) / 60.0, 1e-6);

    host->play();
    ASSERT_TRUE(waitForFrames(*host, 10));
    EXPECT_GT(host->latestFrame()->step, step + 1);
}

TEST_F(SimulationHostTest, PausedHostUsesNoProcessorTime)
{
    ASSERT_TRUE(startScene(lightValues()));
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 10));
    host->pause();
    QTest::qWait(50);
    const double cpuBefore = processCpuSeconds();
    QTest::qWait(500);
    // Waiting on a condition variable, not spinning: a spinning thread would burn the whole 0.5 s.
    EXPECT_LT(processCpuSeconds() - cpuBefore, 0.1);
}

TEST_F(SimulationHostTest, ResetToRestReturnsToTheGroomsRestFrame)
{
    ASSERT_TRUE(startScene(lightValues()));
    const FramePtr rest = host->latestFrame();
    ASSERT_TRUE(rest);
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 30));
    host->pause();
    QTest::qWait(50);
    const FramePtr moved = host->latestFrame();
    float largestMove = 0.0f;
    for (std::size_t i = 0; i < rest->strands.positions.size(); ++i)
        largestMove = std::max(largestMove, glm::distance(moved->strands.positions[i], rest->strands.positions[i]));
    ASSERT_GT(largestMove, 1e-3f) << "the hair should have left its rest shape before the reset";

    const std::uint64_t beforeReset = host->publishedFrames();
    host->resetToRest();
    ASSERT_TRUE(waitForFramesSince(*host, beforeReset, 1));
    const FramePtr again = host->latestFrame();
    EXPECT_EQ(again->step, 0u);
    EXPECT_EQ(again->simulatedSeconds, 0.0);
    EXPECT_EQ(again->groomVersion, rest->groomVersion);
    ASSERT_EQ(again->strands.offsets, rest->strands.offsets);
    for (std::size_t i = 0; i < rest->strands.positions.size(); ++i)
        ASSERT_LT(glm::distance(again->strands.positions[i], rest->strands.positions[i]), 1e-5f) << "point " << i;
    QTest::qWait(200);
    EXPECT_EQ(host->latestFrame(), again) << "a reset while paused publishes one frame";

    // While playing, the hair restarts from rest and keeps going.
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 60));
    const std::uint64_t before = host->latestFrame()->step;
    host->resetToRest();
    ASSERT_TRUE(waitForFrames(*host, 3));
    EXPECT_LT(host->latestFrame()->step, before);
    EXPECT_TRUE(host->isPlaying());
}

TEST_F(SimulationHostTest, GroomParameterRegroomsOnTheSimulationThreadKeepingTheOldFrameMeanwhile)
{
    ASSERT_TRUE(startScene(lightValues()));
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 10));
    QSignalSpy ready(host.get(), &SimulationHost::sceneReady);
    host->setParameters(with(lightValues(), { { Param::Segments, 7.0 } })); // returns at once: see GuiThreadCalls...
    // Until the new groom is ready the previous frames stay visible, each whole (a bounded loop: 2 ms
    // per look, a hang guard of kSceneWaitMs).
    for (int look = 0; ready.count() == 0 && look < kSceneWaitMs / 2; ++look) {
        const FramePtr frame = host->latestFrame();
        ASSERT_TRUE(isWhole(frame));
        if (frame->groomVersion == 1) {
            EXPECT_EQ(frame->strands.pointsIn(0), 16u);
        }
        QTest::qWait(2);
    }
    ASSERT_EQ(ready.count(), 1);
    ASSERT_TRUE(waitForFrames(*host, 10));
    const FramePtr frame = host->latestFrame();
    ASSERT_TRUE(isWhole(frame));
    EXPECT_EQ(frame->groomVersion, 2u);
    for (std::size_t s = 0; s < frame->strands.strandCount(); ++s)
        ASSERT_EQ(frame->strands.pointsIn(s), 8u);
    EXPECT_GE(frame->step, 10u); // playing carried on with the new groom

    // simulate_all_strands regrooms as well: every drawn strand is simulated.
    host->setParameters(with(lightValues(), { { Param::Segments, 7.0 }, { Param::SimulateAllStrands, 1.0 } }));
    ASSERT_TRUE(ready.wait(kSceneWaitMs));
    ASSERT_TRUE(waitForFrames(*host, 2));
    EXPECT_EQ(host->latestFrame()->groomVersion, 3u);
    EXPECT_EQ(host->latestFrame()->simulatedStrands, host->latestFrame()->strands.strandCount());
}

TEST_F(SimulationHostTest, RefusedSceneReportsAnErrorAndThePreviousSceneKeepsPublishing)
{
    ASSERT_TRUE(startScene(lightValues()));
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 5));
    const std::size_t strands = host->latestFrame()->strands.strandCount();
    QSignalSpy errors(host.get(), &SimulationHost::errorOccurred);
    QSignalSpy ready(host.get(), &SimulationHost::sceneReady);

    // A growth map painted all zero grows no hair.
    host->setScene(defaultHead().mesh, std::vector<float>(defaultHead().growthWeights.size(), 0.0f), lightValues());
    ASSERT_TRUE(errors.wait(kSceneWaitMs));
    EXPECT_NE(errors.front().front().toString().indexOf(QStringLiteral("growth map")), -1)
        << errors.front().front().toString().toStdString();
    ASSERT_TRUE(waitForFrames(*host, 10));
    EXPECT_EQ(host->latestFrame()->groomVersion, 1u);
    EXPECT_EQ(host->latestFrame()->strands.strandCount(), strands);

    // A head without triangles cannot be groomed either.
    host->setScene(TriangleMesh{}, {}, lightValues());
    ASSERT_TRUE(errors.wait(kSceneWaitMs));
    EXPECT_EQ(errors.count(), 2);
    EXPECT_NE(errors.at(1).front().toString().indexOf(QStringLiteral("head")), -1);
    ASSERT_TRUE(waitForFrames(*host, 10));
    EXPECT_EQ(host->latestFrame()->groomVersion, 1u);
    EXPECT_EQ(ready.count(), 0);
    EXPECT_TRUE(host->isPlaying());

    // The previous scene still takes parameter changes, regrooms included (on the previous head).
    host->setParameters(with(lightValues(), { { Param::Segments, 5.0 } }));
    ASSERT_TRUE(ready.wait(kSceneWaitMs));
    EXPECT_EQ(host->latestFrame()->groomVersion, 2u);
    EXPECT_EQ(host->latestFrame()->strands.strandCount(), strands);
    EXPECT_EQ(host->latestFrame()->strands.pointsIn(0), 6u);
}

TEST_F(SimulationHostTest, FramesAreNeverHalfBuilt)
{
    ASSERT_TRUE(startScene(lightValues()));
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 3));
    // A second reader thread (like a render thread) beside the GUI thread, while the simulation
    // thread steps, regrooms and resets.
    std::atomic<bool> stop{ false };
    std::atomic<int> readerFailures{ 0 };
    std::atomic<long> readerFrames{ 0 };
    std::thread reader([&] {
        FramePtr previous;
        while (!stop.load()) {
            const FramePtr frame = host->latestFrame();
            if (!isWhole(frame))
                ++readerFailures;
            if (previous && frame->groomVersion < previous->groomVersion)
                ++readerFailures;
            previous = frame;
            ++readerFrames;
        }
    });
    // At least 300 looks (one every millisecond or more) and two completed regrooms (they take
    // longer under the sanitizers); a new request every 50 looks. The bound only catches a hang.
    int round = 0;
    const auto regroomedTwice = [&] { return host->latestFrame()->groomVersion >= 3; };
    for (int look = 0; (look < 300 || !regroomedTwice()) && look < kSceneWaitMs; ++look) {
        if (look >= round * 50) {
            ++round;
            host->setParameters(
                with(lightValues(), { { Param::Segments, 6.0 + round % 3 }, { Param::Gravity, round } }));
            if (round % 2 == 0)
                host->resetToRest();
        }
        const FramePtr frame = host->latestFrame();
        EXPECT_TRUE(isWhole(frame)); // not ASSERT: the reader thread must be joined
        QTest::qWait(1);
    }
    stop.store(true);
    reader.join();
    EXPECT_EQ(readerFailures.load(), 0);
    EXPECT_GT(readerFrames.load(), 100);
    EXPECT_GE(host->latestFrame()->groomVersion, 3u);
}

TEST_F(SimulationHostTest, SlowStepsRunInSlowMotionShedSubstepsAndGetThemBackWhenCheap)
{
    // Step costs chosen by the test, through the pacer's clock: every read costs one time step, so a
    // paced step (three reads) costs two time steps of which one is the solver's.
    const double kTimeStep = solverSettingsFrom(lightValues()).timeStepSeconds;
    useTestClock();
    ASSERT_TRUE(startScene(with(lightValues(), { { Param::Substeps, 8.0 } })));
    ASSERT_EQ(host->effectiveSubsteps(), 8);
    clock->setPerRead(kTimeStep);
    host->play();
    ASSERT_TRUE(waitUntil([&] { return host->effectiveSubsteps() < 8; }));
    // After kReduceAfterSteps steps over budget: a solver that takes the whole time step at 8
    // substeps leaves no room for even one within kBudgetShare, so the floor of 1 is taken.
    EXPECT_EQ(host->effectiveSubsteps(), 1);
    ASSERT_TRUE(waitForFrames(*host, 3));
    const FramePtr slow = host->latestFrame();
    EXPECT_GE(slow->step, static_cast<std::uint64_t>(SimulationHostPacer::kReduceAfterSteps));
    EXPECT_TRUE(slow->fallingBehind);
    // At least four reads of one time step each between step starts: a quarter of real time or less.
    EXPECT_GT(slow->timeScale, 0.0);
    EXPECT_LE(slow->timeScale, 0.25 + 1e-9);

    // Cheap steps (a tenth of a time step per read) keep real time with room to spare: the substeps
    // come back one every kRestoreAfterSteps steps up to the request, and the frames say all is well.
    clock->setPerRead(kTimeStep / 10.0);
    const std::uint64_t cheapFrom = host->latestFrame()->step;
    ASSERT_TRUE(waitUntil([&] { return host->effectiveSubsteps() == 8; }, kSceneWaitMs));
    EXPECT_GE(host->latestFrame()->step, cheapFrom + 7 * SimulationHostPacer::kRestoreAfterSteps);
    ASSERT_TRUE(waitUntil([&] { return !host->latestFrame()->fallingBehind; }, kSceneWaitMs));
    EXPECT_EQ(host->latestFrame()->timeScale, 1.0);
    EXPECT_EQ(host->effectiveSubsteps(), 8);
}

TEST_F(SimulationHostTest, FallingBehindOnTheRealClockShedsSubsteps)
{
    // End to end on the steady clock: every strand of the default density at 32 substeps and 1 ms
    // time steps is more than any machine steps in real time. Only the outcome is checked, with
    // waits that catch a hang (the decisions themselves are counted in the tests above and below).
    const ParameterValues heavy = with(lightValues(),
        { { Param::Density, 8.0 }, { Param::SimulateAllStrands, 1.0 }, { Param::Substeps, 32.0 },
            { Param::TimeStep, 0.001 },
            // The grid's pass per substep would make the drape before
            // sceneReady take minutes on a loaded 2-core machine; the
            // scene is too heavy for real time without it.
            { Param::Volume, 0.0 } });
    ASSERT_TRUE(startScene(heavy));
    EXPECT_EQ(host->effectiveSubsteps(), 32);
    host->play();
    ASSERT_TRUE(waitUntil([&] { return host->effectiveSubsteps() < 32; }, kSceneWaitMs));
    EXPECT_GE(host->effectiveSubsteps(), 1);
    ASSERT_TRUE(waitForFrames(*host, 2, kSceneWaitMs));
    const FramePtr frame = host->latestFrame();
    ASSERT_TRUE(isWhole(frame));
    EXPECT_TRUE(frame->fallingBehind) << "fewer substeps than asked";
    EXPECT_GT(frame->timeScale, 0.0);
    EXPECT_LE(frame->timeScale, 1.0);
}

// The two tests below check that destruction does not wait for work in flight: the thread is gone
// afterwards (counted), and the timer is only a hang guard (30 s, times the sanitizer factor), far
// above anything a healthy host takes however loaded the machine.
constexpr int kHangGuardMs = 30000 * WISP_SLOW_BUILD_FACTOR;

TEST_F(SimulationHostTest, DestroyingWhilePlayingJoinsTheThread)
{
    host.reset();
    const long before = threadCount();
    host = std::make_unique<SimulationHost>();
    ASSERT_TRUE(startScene(lightValues()));
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 10));
    EXPECT_GT(threadCount(), before);
    const auto start = std::chrono::steady_clock::now();
    host.reset();
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(kHangGuardMs));
    EXPECT_LE(threadCount(), before);
}

TEST_F(SimulationHostTest, DestroyingMidRegroomDropsQueuedWorkAndJoins)
{
    host.reset();
    const long before = threadCount();
    host = std::make_unique<SimulationHost>();
    ASSERT_TRUE(startScene(lightValues()));
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 5));
    QSignalSpy ready(host.get(), &SimulationHost::sceneReady);
    host->setScene(defaultHead().mesh, defaultHead().growthWeights, ParameterValues{}); // the default groom
    QTest::qWait(20); // let the simulation thread start grooming
    host->setParameters(with(ParameterValues{}, { { Param::Segments, 20.0 } })); // queued behind it, dropped
    const auto start = std::chrono::steady_clock::now();
    host.reset();
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(kHangGuardMs));
    EXPECT_LE(threadCount(), before);
}

TEST_F(SimulationHostTest, RequestsBeforeAnySceneAreHarmless)
{
    host->play();
    host->stepOnce();
    host->resetToRest();
    host->setParameters(lightValues());
    QTest::qWait(50);
    EXPECT_EQ(host->publishedFrames(), 0u);
    EXPECT_EQ(host->latestFrame(), nullptr);
    // Playing before the scene exists: it starts moving as soon as it is groomed.
    ASSERT_TRUE(startScene(lightValues()));
    ASSERT_TRUE(waitForFrames(*host, 5));
    EXPECT_GT(host->latestFrame()->step, 0u);
}

// The pacing policy on made-up timings (seconds): no threads, no clock.

TEST(SimulationHostPacer, KeepsAFixedCadenceAndCatchesUpASmallDelay)
{
    SimulationHostPacer pacer;
    const double dt = 1.0 / 60.0;
    pacer.setRequestedSubsteps(2);
    pacer.restart(10.0);
    EXPECT_EQ(pacer.dueSeconds(), 10.0);
    for (int i = 0; i < 100; ++i) {
        const double start = pacer.dueSeconds() + 0.0002; // wake-ups are a little late
        const auto report = pacer.finishStep(start, start + 0.002, 0.0015, dt);
        EXPECT_FALSE(report.fallingBehind);
        EXPECT_EQ(report.timeScale, 1.0);
        EXPECT_FALSE(report.substepsChanged);
    }
    EXPECT_NEAR(pacer.dueSeconds(), 10.0 + 100 * dt, 1e-9); // no drift from the late wake-ups
    // One wake-up late by most of a step: the next step stays on the cadence (it comes sooner, so
    // the pair catches up) and the late frame is not called slow motion.
    const double cadence = pacer.dueSeconds();
    const double late = cadence + 0.8 * dt;
    const auto report = pacer.finishStep(late, late + 0.002, 0.0015, dt);
    EXPECT_NEAR(pacer.dueSeconds(), cadence + dt, 1e-9);
    EXPECT_FALSE(report.fallingBehind);
    EXPECT_EQ(pacer.substeps(), 2);
}

TEST(SimulationHostPacer, TheRateMeansTheSameAtAnyTimeStep)
{
    // 1 ms steps costing 0.5 ms, then one 20 ms stall (another program took the core): the rate is
    // measured over wall seconds, not over a count of steps, so one stall is not slow motion...
    SimulationHostPacer pacer;
    const double dt = 0.001;
    pacer.setRequestedSubsteps(1);
    pacer.restart(0.0);
    for (int i = 0; i < 1000; ++i) {
        const double start = pacer.dueSeconds();
        EXPECT_FALSE(pacer.finishStep(start, start + 0.0005, 0.0004, dt).fallingBehind);
    }
    const double stalled = pacer.dueSeconds() + 0.020;
    EXPECT_FALSE(pacer.finishStep(stalled, stalled + 0.0005, 0.0004, dt).fallingBehind);
    // ...but steps of 2 ms are half speed: said within a tenth of a second, measured to a few
    // percent once the earlier real-time second has faded (two kRateSeconds).
    double now = stalled + 0.0005;
    auto slowSteps = [&](int steps) {
        SimulationHostPacer::StepReport report;
        for (int i = 0; i < steps; ++i) {
            const double start = std::max(now, pacer.dueSeconds());
            now = start + 0.002;
            report = pacer.finishStep(start, now, 0.0019, dt);
        }
        return report;
    };
    EXPECT_TRUE(slowSteps(50).fallingBehind);
    const SimulationHostPacer::StepReport report = slowSteps(1000);
    EXPECT_TRUE(report.fallingBehind);
    EXPECT_NEAR(report.timeScale, 0.5, 0.02);
}

TEST(SimulationHostPacer, SlowStepsAreNotChasedAndShedSubstepsDownToWhatFits)
{
    SimulationHostPacer pacer;
    const double dt = 1.0 / 60.0;
    pacer.setRequestedSubsteps(8);
    pacer.restart(0.0);
    double now = 0.0;
    SimulationHostPacer::StepReport report;
    // 8 substeps of 6 ms plus 2 ms for the frame: 50 ms a step, three times the time step.
    for (int i = 0; i < SimulationHostPacer::kReduceAfterSteps - 1; ++i) {
        const double start = std::max(now, pacer.dueSeconds());
        now = start + 0.050;
        report = pacer.finishStep(start, now, 0.048, dt);
        EXPECT_TRUE(report.fallingBehind);
        EXPECT_FALSE(report.substepsChanged);
        EXPECT_LE(pacer.dueSeconds(), now) << "the next step starts at once";
        EXPECT_GE(pacer.dueSeconds(), now - dt) << "no backlog of more than one step";
    }
    EXPECT_NEAR(report.timeScale, dt / 0.050, 0.02);
    const double start = std::max(now, pacer.dueSeconds());
    now = start + 0.050;
    report = pacer.finishStep(start, now, 0.048, dt);
    EXPECT_TRUE(report.substepsChanged);
    // floor((0.8 * 16.7 ms - 2 ms) / 6 ms) = 1
    EXPECT_EQ(pacer.substeps(), 1);
    EXPECT_EQ(pacer.requestedSubsteps(), 8);

    // At 1 substep a step costs 8 ms: real time again (once the slow second has faded from the
    // rate), but still reported as behind (fewer substeps).
    for (int i = 0; i < 150; ++i) {
        const double s = std::max(now, pacer.dueSeconds());
        now = s + 0.008;
        report = pacer.finishStep(s, now, 0.006, dt);
    }
    EXPECT_EQ(report.timeScale, 1.0);
    EXPECT_TRUE(report.fallingBehind);
    // 2 substeps would cost 14 ms, over the restore share: stays at 1 (no flapping).
    for (int i = 0; i < 3 * SimulationHostPacer::kRestoreAfterSteps; ++i) {
        const double s = std::max(now, pacer.dueSeconds());
        now = s + 0.008;
        pacer.finishStep(s, now, 0.006, dt);
    }
    EXPECT_EQ(pacer.substeps(), 1);
}

TEST(SimulationHostPacer, GivesSubstepsBackOneAtATimeWhenThereIsHeadroom)
{
    SimulationHostPacer pacer;
    const double dt = 1.0 / 60.0;
    pacer.setRequestedSubsteps(4);
    pacer.restart(0.0);
    double now = 0.0;
    auto run = [&](int steps, double perSubstep) {
        int changes = 0;
        for (int i = 0; i < steps; ++i) {
            const double start = std::max(now, pacer.dueSeconds());
            const double solver = perSubstep * pacer.substeps();
            now = start + solver + 0.001;
            changes += pacer.finishStep(start, now, solver, dt).substepsChanged ? 1 : 0;
        }
        return changes;
    };
    run(SimulationHostPacer::kReduceAfterSteps, 0.010); // 41 ms a step: over budget
    EXPECT_EQ(pacer.substeps(), 1);
    // The machine got faster (another program quit): 1 ms a substep.
    run(SimulationHostPacer::kRestoreAfterSteps - 1, 0.001);
    EXPECT_EQ(pacer.substeps(), 1);
    run(1, 0.001);
    EXPECT_EQ(pacer.substeps(), 2);
    run(2 * SimulationHostPacer::kRestoreAfterSteps, 0.001);
    EXPECT_EQ(pacer.substeps(), 4);
    run(5 * SimulationHostPacer::kRestoreAfterSteps, 0.001);
    EXPECT_EQ(pacer.substeps(), 4) << "never above the request";
    const auto report = pacer.finishStep(now, now + 0.005, 0.004, dt);
    EXPECT_FALSE(report.fallingBehind);

    // Never below 1, however slow.
    run(10 * SimulationHostPacer::kReduceAfterSteps, 0.5);
    EXPECT_EQ(pacer.substeps(), 1);
    // A new request starts over from it.
    pacer.setRequestedSubsteps(3);
    EXPECT_EQ(pacer.substeps(), 3);
}
