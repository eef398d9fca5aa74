#pragma once
// The simulation thread's clock keeper: when the next step is due, whether the solver keeps real
// time, and how many substeps it can afford. It is plain arithmetic on seconds that the caller
// measured, so the policy is tested without threads, clocks or sleeping.
//
// Policy (why): a step is due every time step of wall clock, on a fixed cadence so that small
// wake-up delays are caught up and the average rate stays exact. When the solver cannot keep up,
// catching up would make every step later than the one before (the spiral of death), so a backlog of
// more than one step is dropped instead: steps then run back to back and time slows down, which the
// frames report as fallingBehind with timeScale = simulated / wall seconds. If that persists, the
// substeps are lowered (never below 1) to what fits the time step, and raised again one at a time
// once there is clear headroom; frames report fallingBehind while the substeps are below the
// artist's request, even when real time is kept again (timeScale 1).
//
// Thread: owned and called by the simulation thread (SimulationHost); tests call it anywhere.

#include <algorithm>
#include <cmath>

namespace wisp {

class SimulationHostPacer {
public:
    struct StepReport {
        bool fallingBehind = false; // below real time, or running fewer substeps than requested
        double timeScale = 1.0; // simulated seconds per wall-clock second; 1 while keeping up
        bool substepsChanged = false; // substeps() changed: the solver should use it from the next step
    };

    // Wall seconds above this many simulated seconds is slow motion; below, the difference is the
    // scheduler's jitter.
    static constexpr double kSlowFactor = 1.1;
    // The rate is simulated over wall seconds with both sums fading over this much wall clock, so
    // it means the same at any time step: a single late wake-up (caught up by the next step) moves it
    // a few percent, sustained slowness shows within a few steps and is exact within a second.
    static constexpr double kRateSeconds = 0.5;
    // Consecutive over-budget steps before substeps are lowered (a third of a second at 60 Hz):
    // long enough to ignore a hiccup, short enough that an artist does not watch slow motion for long.
    static constexpr int kReduceAfterSteps = 20;
    // Consecutive steps with headroom before one substep is given back (two seconds at 60 Hz).
    static constexpr int kRestoreAfterSteps = 120;
    // Lowered substeps aim at this share of the time step, leaving room for frame building and jitter.
    static constexpr double kBudgetShare = 0.8;
    // A substep is given back only if the step would then still cost less than this share; the gap to
    // kBudgetShare keeps the count from flapping between two values.
    static constexpr double kRestoreShare = 0.6;

    // Thread: simulation. Playing (re)starts at `nowSeconds`: the first step is due at once, and the
    // measured rate starts afresh (a pause or a regroom is not slowness).
    void restart(double nowSeconds)
    {
        m_dueSeconds = nowSeconds;
        m_hasLastStart = false;
        m_simulatedSum = 0.0;
        m_wallSum = 0.0;
        m_overBudgetSteps = 0;
        m_headroomSteps = 0;
    }

    // Thread: simulation. When the next paced step should start, in the caller's seconds.
    double dueSeconds() const { return m_dueSeconds; }

    // Thread: simulation. The artist's substeps (a new request, or a new groom): the effective count
    // returns to it and adapts from there.
    void setRequestedSubsteps(int substeps)
    {
        m_requested = std::max(1, substeps);
        m_substeps = m_requested;
        m_overBudgetSteps = 0;
        m_headroomSteps = 0;
    }
    int requestedSubsteps() const { return m_requested; }
    // Thread: simulation. What the solver should run now, 1 ... requestedSubsteps().
    int substeps() const { return m_substeps; }

    // Thread: simulation. After a paced step that started at `startSeconds` and was published at
    // `endSeconds`, `solverSeconds` of which the solver took (run at substeps()); schedules the next.
    StepReport finishStep(double startSeconds, double endSeconds, double solverSeconds, double timeStepSeconds)
    {
        const double dt = timeStepSeconds;
        const double work = std::max(0.0, endSeconds - startSeconds);
        // Wall seconds between step starts is what simulated time is measured against; for the
        // first step after restart() its own cost is the best guess.
        const double interval = m_hasLastStart ? std::max(0.0, startSeconds - m_lastStartSeconds) : std::max(dt, work);
        m_lastStartSeconds = startSeconds;
        m_hasLastStart = true;
        const double fade = std::exp(-interval / kRateSeconds);
        m_simulatedSum = m_simulatedSum * fade + dt;
        m_wallSum = m_wallSum * fade + interval;

        // Fixed cadence; a backlog of more than one step is dropped rather than chased.
        m_dueSeconds += dt;
        if (m_dueSeconds < endSeconds - dt)
            m_dueSeconds = endSeconds;

        StepReport report;
        const double perSubstep = solverSeconds / m_substeps;
        const double otherWork = std::max(0.0, work - solverSeconds); // building and publishing the frame
        if (work > dt) {
            ++m_overBudgetSteps;
            m_headroomSteps = 0;
        } else {
            m_overBudgetSteps = 0;
        }
        if (m_overBudgetSteps >= kReduceAfterSteps && m_substeps > 1) {
            const double fit = perSubstep > 0.0 ? std::floor((kBudgetShare * dt - otherWork) / perSubstep) : 0.0;
            m_substeps = std::clamp(static_cast<int>(std::max(fit, 1.0)), 1, m_substeps - 1);
            m_overBudgetSteps = 0;
            report.substepsChanged = true;
        } else if (m_substeps < m_requested && work <= dt) {
            const double predicted = otherWork + perSubstep * (m_substeps + 1);
            m_headroomSteps = predicted < kRestoreShare * dt ? m_headroomSteps + 1 : 0;
            if (m_headroomSteps >= kRestoreAfterSteps) {
                ++m_substeps;
                m_headroomSteps = 0;
                report.substepsChanged = true;
            }
        }

        const bool slow = m_wallSum > kSlowFactor * m_simulatedSum;
        report.timeScale = slow ? m_simulatedSum / m_wallSum : 1.0;
        report.fallingBehind = slow || m_substeps < m_requested;
        return report;
    }

private:
    double m_dueSeconds = 0.0;
    double m_lastStartSeconds = 0.0;
    bool m_hasLastStart = false;
    double m_simulatedSum = 0.0; // simulated seconds, fading with wall clock (kRateSeconds)
    double m_wallSum = 0.0; // wall seconds, fading alike
    int m_requested = 1;
    int m_substeps = 1;
    int m_overBudgetSteps = 0;
    int m_headroomSteps = 0;
};

} // namespace wisp
