// The simulation host as the editor drives it: requests from the GUI thread, frames back from the
// simulation thread. The checks are on published frames only (where the tips are, what the counters
// say), not on the solver, and the GUI thread's event loop runs through QTest::qWait / QSignalSpy.
// Here: frames, real-time pacing and parameters. Pause, step, reset, threads and lifetime are in
// SimulationHostControlTest.cpp; the pacing policy on its own, with made-up timings, in
// SimulationHostPacerTest.cpp.
#include "SimulationHostTestSupport.h"

using namespace wisp;
using namespace wisp::test;

namespace {

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
    // The sanitizer build (ten times slower, and more for the solver's SIMD) keeps the light groom's
    // keys: its drape of every strand at density 8 took over 20 minutes there, and the keys at 32
    // substeps a millisecond are far behind real time in that build already.
    constexpr bool kSlowBuild = WISP_SLOW_BUILD_FACTOR > 1;
    const ParameterValues heavy = with(lightValues(),
        { { Param::Density, kSlowBuild ? 2.0 : 8.0 }, { Param::SimulateAllStrands, kSlowBuild ? 0.0 : 1.0 },
            { Param::Substeps, 32.0 }, { Param::TimeStep, 0.001 },
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

} // namespace
