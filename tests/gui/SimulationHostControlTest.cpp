// The simulation host's controls and lifetime: GUI-thread calls never wait for the simulation
// thread, pause / step / reset, frames never half built, destruction joins the thread.
#include "SimulationHostTestSupport.h"

using namespace wisp;
using namespace wisp::test;

namespace {

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
    EXPECT_FALSE(host->isIdle()); // it steps
    host->stepOnce(); // ignored while playing
    host->pause();
    EXPECT_FALSE(host->isPlaying());
    ASSERT_EQ(playing.count(), 2);
    EXPECT_FALSE(playing.at(1).front().toBool());
    // A step that was running when pause() came still lands; then the thread sleeps.
    ASSERT_TRUE(waitUntil([&] { return host->isIdle(); }, kSceneWaitMs));
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
    // Taken with or after the pause: its rest frame (step 0; every frame played had a later step) is
    // the last the simulation thread publishes before it goes back to sleep with nothing to do.
    host->resetToRest();
    ASSERT_TRUE(waitUntil([&] { return host->latestFrame()->step == 0; }, kSceneWaitMs));
    const std::uint64_t wakeups = host->loopWakeups();
    const std::uint64_t published = host->publishedFrames();
    QTest::qWait(500);
    // Waiting on a condition variable, counted: no wakeup at all while nothing is asked (a thread
    // that spun or polled would wake hundreds of times in this half second), and no frame.
    EXPECT_EQ(host->loopWakeups(), wakeups);
    EXPECT_EQ(host->publishedFrames(), published);
    EXPECT_GT(wakeups, 10u) << "the loop's wakeups are counted while it plays";
}

TEST_F(SimulationHostTest, ResetToRestReturnsToTheGroomsRestFrame)
{
    ASSERT_TRUE(startScene(lightValues()));
    const FramePtr rest = host->latestFrame();
    ASSERT_TRUE(rest);
    host->play();
    ASSERT_TRUE(waitForFrames(*host, 30));
    host->pause();
    ASSERT_TRUE(waitUntil([&] { return host->isIdle(); }, kSceneWaitMs)); // the last step has landed
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
                with(lightValues(), { { Param::Segments, 6.0 + round % 3 }, { Param::Gravity, round % 50 } }));
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

TEST_F(SimulationHostTest, DestroyingWhilePlayingJoinsTheThread)
{
    host.reset();
    const long before = threadCount();
    ASSERT_TRUE(playNewHost(10));
    EXPECT_GT(threadCount(), before);
    // Destruction does not wait for work in flight: it returns (guarded) and the thread is gone.
    runWithHangGuard("destroying a playing SimulationHost", [&] { host.reset(); });
    EXPECT_TRUE(threadCountFallsTo(before)) << threadCount() << " threads, " << before << " before";
}

TEST_F(SimulationHostTest, DestroyingMidRegroomDropsQueuedWorkAndJoins)
{
    host.reset();
    const long before = threadCount();
    ASSERT_TRUE(playNewHost(5));
    QSignalSpy ready(host.get(), &SimulationHost::sceneReady);
    host->setScene(defaultHead().mesh, defaultHead().growthWeights, ParameterValues{}); // the default groom
    QTest::qWait(20); // let the simulation thread start grooming
    host->setParameters(with(ParameterValues{}, { { Param::Segments, 20.0 } })); // queued behind it, dropped
    runWithHangGuard("destroying a SimulationHost mid-regroom", [&] { host.reset(); });
    EXPECT_TRUE(threadCountFallsTo(before)) << threadCount() << " threads, " << before << " before";
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

} // namespace
