// The simulation host's pacing policy on its own (SimulationHostPacer), with made-up timings.
#include "SimulationHostTestSupport.h"

using namespace wisp;
using namespace wisp::test;

namespace {

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

} // namespace
