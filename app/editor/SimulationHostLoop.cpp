// SimulationHost's simulation thread: the loop that takes the GUI's requests, (re)grooms, drapes
// and steps the solver at the pacer's rate, and publishes frames.
#include "app/editor/SimulationHost.h"

#include "sim/style/BrushContext.h"

#include "app/editor/SettledScene.h"

#include "app/editor/SimulationHostPacer.h"
#include "sim/solver/HairSimulation.h"
#include "sim/solver/SolverSettings.h"

#include <glm/common.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <exception>
#include <span>
#include <string>
#include <utility>

namespace wisp {

namespace {

using Clock = std::chrono::steady_clock;

// Thread: any. True when `a` and `b` build the same groom: the same Groom-group parameters and the
// same choice of simulated strands. Everything else is a force or solver setting the running
// solver takes without a regroom.
bool sameGroom(const ParameterValues& a, const ParameterValues& b)
{
    for (const ParameterInfo& p : allParameters())
        if ((p.group == ParamGroup::Groom || p.id == Param::SimulateAllStrands) && a.get(p.id) != b.get(p.id))
            return false;
    return true;
}

} // namespace

// Everything the simulation thread owns. It lives on that thread's stack, so nothing else can
// reach the solver: the GUI thread only fills SimulationHost::m_inbox.
//
// Thread: simulation, every member.
class SimulationHost::Loop {
public:
    explicit Loop(SimulationHost& host)
        : m_host(host)
        , m_epoch(Clock::now())
    {
    }

    // Thread: simulation. Takes requests and steps until the host stops.
    void run()
    {
        Inbox taken;
        while (takeRequests(taken)) {
            // A groom takes a while: a host being destroyed meanwhile should not wait for one more.
            // A new style is kept for every later scene; the running hair regrooms with it unless a
            // new scene or new regions are about to regroom anyway.
            if (taken.style) {
                m_style = std::move(*taken.style);
                if (m_sim) {
                    m_sim->setStyle(m_style);
                    if (!taken.scene && !taken.regions && !stopRequested())
                        restyle();
                }
            }
            if (taken.dryers) {
                m_dryers = std::move(*taken.dryers);
                if (m_sim)
                    m_sim->setDryers(m_dryers);
            }
            if (taken.motion)
                adoptMotion(std::move(*taken.motion));
            if (taken.scene && !stopRequested())
                adoptScene(std::move(*taken.scene));
            if (taken.regions && !stopRequested())
                adoptRegions(std::move(*taken.regions));
            if (taken.parameters && !stopRequested())
                adoptParameters(*taken.parameters);
            if (taken.playing != m_playing) {
                m_playing = taken.playing;
                if (m_playing)
                    m_pacer.restart(now());
            }
            if (m_sim && !taken.wettings.empty()) {
                for (const Wetting& wetting : taken.wettings)
                    m_sim->wet(wetting.keyIdentities, wetting.wetness);
                if (!m_playing)
                    m_host.publish(makeFrame());
            }
            if (taken.held) {
                m_held = std::move(*taken.held);
                if (m_sim && applyHeld() && !m_playing)
                    m_host.publish(makeFrame());
            }
            for (Action action : taken.actions) {
                if (action == Action::Step)
                    step(false);
                else
                    resetToRest();
            }
            if (m_playing && m_sim && now() >= m_pacer.dueSeconds())
                step(true);
        }
    }

private:
    // Thread: simulation. The pacer's clock: seconds since the loop started, or the injected clock's.
    double now() const
    {
        if (m_host.m_clock)
            return m_host.m_clock();
        return std::chrono::duration<double>(Clock::now() - m_epoch).count();
    }

    // Thread: simulation. Sleeps until a request arrives or, while playing, the next step is due;
    // then moves the requests out (the lock is held only for that). False when the host stops.
    bool takeRequests(Inbox& taken)
    {
        taken.scene.reset();
        taken.parameters.reset();
        taken.regions.reset();
        taken.actions.clear();
        taken.style.reset();
        taken.dryers.reset();
        taken.held.reset();
        taken.wettings.clear();
        taken.motion.reset();
        // Read before taking the lock: an injected clock may be slow to answer (a test holds it), and
        // the GUI thread's requests must never wait for it.
        const bool injectedStepDue = m_host.m_clock && m_playing && m_sim && now() >= m_pacer.dueSeconds();
        std::unique_lock lock(m_host.m_mutex);
        Inbox& inbox = m_host.m_inbox;
        const auto ready = [&] { return inbox.hasRequests(m_playing); };
        if (m_playing && m_sim && m_host.m_clock) {
            // An injected clock moves on its own terms: look again soon, unless a step is due now.
            if (!injectedStepDue)
                m_host.m_wake.wait_for(lock, std::chrono::milliseconds(kInjectedClockPollMs), ready);
        } else if (m_playing && m_sim) {
            const auto due = m_epoch
                + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(m_pacer.dueSeconds()));
            m_host.m_wake.wait_until(lock, due, ready);
        } else {
            // Nothing to step: idle until asked (isIdle(), which also looks for requests not yet
            // taken).
            m_host.m_idle.store(!ready());
            m_host.m_wake.wait(lock, ready);
            m_host.m_idle.store(false);
        }
        m_host.m_loopWakeups.fetch_add(1, std::memory_order_relaxed);
        if (inbox.stopping)
            return false;
        taken.scene = std::exchange(inbox.scene, std::nullopt);
        taken.parameters = std::exchange(inbox.parameters, std::nullopt);
        taken.regions = std::exchange(inbox.regions, std::nullopt);
        taken.actions.swap(inbox.actions);
        taken.style = std::exchange(inbox.style, std::nullopt);
        taken.dryers = std::exchange(inbox.dryers, std::nullopt);
        taken.held = std::exchange(inbox.held, std::nullopt);
        taken.wettings.swap(inbox.wettings);
        taken.motion = std::exchange(inbox.motion, std::nullopt);
        taken.playing = inbox.playing;
        return true;
    }

    // Thread: simulation.
    bool stopRequested() const
    {
        std::lock_guard lock(m_host.m_mutex);
        return m_host.m_inbox.stopping;
    }

    // Thread: simulation. A new head: groom it, or keep the previous scene and say why not.
    void adoptScene(Scene scene)
    {
        auto next = std::make_unique<HairSimulation>(m_host.m_solverThreads);
        next->setStyle(m_style);
        next->setDryers(m_dryers);
        const Regions& r = scene.regions;
        std::string error;
        try {
            HeadModelPtr head = scene.head ? scene.head : std::make_shared<const HeadModel>(std::move(scene.mesh));
            error = r.fromParameters ? next->setup(std::move(head), r.regions.front().weights, scene.values)
                                     : next->setup(std::move(head), r.regions, r.soloId, scene.values);
        } catch (const std::exception& e) {
            error = std::string("groom: ") + e.what(); // sim/ does not throw, but memory can run out
        }
        if (!error.empty()) {
            m_host.postError(error);
            return;
        }
        m_sim = std::move(next);
        m_regions = std::move(scene.regions);
        m_step = 0;
        m_simulatedSeconds = 0.0;
        m_pivotHead = pivotOf(m_sim->head());
        placeHeadAtStart();
        groomed(scene.values, true);
    }

    // Thread: simulation. New regions for the running head: regroom in place, keeping the motion.
    void adoptRegions(Regions regions)
    {
        if (!m_sim)
            return;
        if (std::string error = regroom(regions, m_values); !error.empty()) {
            m_host.postError(error);
            return;
        }
        m_regions = std::move(regions);
    }

    // Thread: simulation. The running hair with new salon edits (already given to m_sim).
    void restyle()
    {
        if (std::string error = regroom(m_regions, m_values); !error.empty()) {
            m_host.postError(error);
            return;
        }
        // Combed hair too soft to hold its shape under gravity: no rest shape can keep it there.
        if (const float gap = m_sim->worstRestGapMetres(); gap > kRestGapToReportMetres)
            m_host.postError("Some combed hair is too soft to stay where it was combed (up to "
                + std::to_string(static_cast<int>(std::lround(gap * 100.0f)))
                + " cm off): spray it with hairspray to hold the shape");
    }
    static constexpr float kRestGapToReportMetres = 0.03f;

    // Thread: simulation. Puts the comb's strands where it holds them; true if any is held.
    bool applyHeld()
    {
        bool any = false;
        for (const HeldStrand& h : m_held)
            any = m_sim->holdStrand(h.identity, h.positions) || any;
        return any;
    }

    // Thread: simulation. New parameters: regroom if the groom's own parameters changed, otherwise
    // (and also when that regroom is refused) hand the forces to the running solver.
    void adoptParameters(const ParameterValues& values)
    {
        if (!m_sim)
            return; // nothing runs yet; the next scene brings its own values
        const bool refusedBefore = m_refusedGroom && sameGroom(values, *m_refusedGroom);
        if (!sameGroom(values, m_groomedWith) && !refusedBefore) {
            if (std::string error = regroom(m_regions, values); !error.empty()) {
                m_refusedGroom = values; // do not regroom (and report) the same refusal on every force change
                m_host.postError(error);
            }
        }
        const bool newRequest = values.getInt(Param::Substeps) != m_pacer.requestedSubsteps();
        const int substeps = newRequest ? values.getInt(Param::Substeps) : m_pacer.substeps();
        if (std::string error = m_sim->applyForces(withSubsteps(values, substeps)); !error.empty()) {
            m_host.postError(error);
            return;
        }
        m_values = values;
        if (newRequest)
            m_pacer.setRequestedSubsteps(substeps);
        m_host.m_effectiveSubsteps.store(m_pacer.substeps());
    }

    // Thread: simulation. Regrooms the running simulation (HairSimulation::regroom keeps the
    // strands' motion, and the running groom when it refuses). A scene given by one growth map
    // takes its wisp parameters from `values`.
    std::string regroom(Regions& regions, const ParameterValues& values)
    {
        if (regions.fromParameters)
            regions.regions.front().values = values;
        std::string error;
        try {
            error = m_sim->regroom(regions.regions, regions.soloId, values);
        } catch (const std::exception& e) {
            error = std::string("groom: ") + e.what();
        }
        if (error.empty())
            groomed(values);
        return error;
    }

    // Thread: simulation. After a (re)groom: the new layout's first frame, and sceneReady. A new
    // scene starts draped (hanging at rest under gravity); a regroom keeps the hair's motion.
    void groomed(const ParameterValues& values, bool drape = false)
    {
        m_values = values;
        m_groomedWith = values;
        m_refusedGroom.reset();
        ++m_groomVersion;
        m_groomShape = groomShapeOf(*m_sim);
        m_pacer.setRequestedSubsteps(values.getInt(Param::Substeps));
        // The groom just took these values, so the solver takes them with fewer substeps too.
        [[maybe_unused]] const bool applied = m_sim->applyForces(withSubsteps(values, m_pacer.substeps())).empty();
        assert(applied);
        m_host.m_effectiveSubsteps.store(m_pacer.substeps());
        if (drape)
            m_sim->drapeAtRest(
                HairSimulation::kDrapeMaxSteps, kDrapeStillMetres, [this] { return stopRequested(); },
                m_values.getInt(Param::Substeps)); // as asked, not as the pacer runs now
        if (m_playing)
            m_pacer.restart(now()); // the groom's duration is not the solver falling behind
        m_host.publish(makeFrame());
        m_host.postSceneReady();
    }

    // Thread: simulation. One solver step and its frame. A paced step (playing) is timed against the
    // wall clock and may change the substeps for the next one; stepOnce's is not paced.
    void step(bool paced)
    {
        if (!m_sim)
            return;
        const double start = now();
        // The head's pose at the end of this step; the solver moves the roots there over its substeps.
        moveHeadTo(m_simulatedSeconds + m_sim->solver().settings().timeStepSeconds);
        m_sim->step();
        applyHeld();
        const double solverSeconds = now() - start;
        const double timeStep = m_sim->solver().settings().timeStepSeconds;
        ++m_step;
        m_simulatedSeconds += timeStep;
        std::shared_ptr<Frame> frame = makeFrame();
        frame->stepMilliseconds = solverSeconds * 1000.0;
        if (paced) {
            const SimulationHostPacer::StepReport report = m_pacer.finishStep(start, now(), solverSeconds, timeStep);
            frame->fallingBehind = report.fallingBehind;
            frame->timeScale = report.timeScale;
            if (report.substepsChanged) {
                // The requested values were accepted before, so fewer substeps are too.
                [[maybe_unused]] const bool applied
                    = m_sim->applyForces(withSubsteps(m_values, m_pacer.substeps())).empty();
                assert(applied);
                m_host.m_effectiveSubsteps.store(m_pacer.substeps());
            }
        }
        m_host.publish(std::move(frame));
    }

    // Thread: simulation. Back to rest as the hair hangs there (draped under gravity), step 0.
    void resetToRest()
    {
        if (!m_sim)
            return;
        m_simulatedSeconds = 0.0;
        placeHeadAtStart();
        m_sim->drapeAtRest(
            HairSimulation::kDrapeMaxSteps, kDrapeStillMetres, [this] { return stopRequested(); },
            m_values.getInt(Param::Substeps)); // as asked, not as the pacer runs now
        m_step = 0;
        m_simulatedSeconds = 0.0;
        if (m_playing)
            m_pacer.restart(now()); // the drape's duration is not the solver falling behind
        m_host.publish(makeFrame());
    }

    // Thread: simulation. A frame of the solver's current state; not yet shared with anyone.
    std::shared_ptr<Frame> makeFrame() const
    {
        auto frame = std::make_shared<Frame>();
        frame->step = m_step;
        frame->groomVersion = m_groomVersion;
        frame->simulatedSeconds = m_simulatedSeconds;
        fillFrame(*m_sim, m_values, *frame);
        frame->groomShape = m_groomShape;
        frame->headToWorld = m_sim->solver().headTransform();
        frame->headTranslationMetres = m_headPose.translationMetres;
        frame->headRotation = m_headPose.rotation;
        frame->fallingBehind = m_pacer.substeps() < m_pacer.requestedSubsteps();
        return frame;
    }

    // Thread: simulation. A new head motion: the head eases from where it is now to the new motion
    // over the next steps (paused, at the next step: the roots move only when the solver steps, so
    // moving the head alone would tear it from its hair).
    void adoptMotion(HeadMotion motion)
    {
        m_motion = std::move(motion);
        m_easeFrom = m_headPose;
        m_easeStartSeconds = m_simulatedSeconds;
    }

    // Thread: simulation. The head's pose at simulated time `t`: the motion's, eased in from the
    // pose the head had when the motion last changed.
    HeadPose headPoseAt(double t) const
    {
        const HeadPose target = m_motion.poseAt(t);
        const double s = std::clamp((t - m_easeStartSeconds) / kHeadEaseSeconds, 0.0, 1.0);
        if (s >= 1.0)
            return target;
        const float eased = static_cast<float>(s * s * (3.0 - 2.0 * s)); // smoothstep: C1 at both ends
        HeadPose pose;
        pose.translationMetres = glm::mix(m_easeFrom.translationMetres, target.translationMetres, eased);
        pose.rotation = glm::normalize(glm::slerp(m_easeFrom.rotation, target.rotation, eased));
        return pose;
    }

    // Thread: simulation. Gives the solver the head at simulated time `t`.
    void moveHeadTo(double t)
    {
        m_headPose = headPoseAt(t);
        m_sim->solver().setHeadTransform(headToWorld(m_headPose, m_pivotHead));
    }

    // Thread: simulation. The head where the motion starts (t = 0), with nothing to ease: a new
    // scene and a reset place the hair there at rest (the drape reads the head transform).
    void placeHeadAtStart()
    {
        m_easeStartSeconds = -kHeadEaseSeconds;
        moveHeadTo(0.0);
    }

    // Thread: any. `values` with the solver's substeps replaced by what the machine affords now.
    static ParameterValues withSubsteps(ParameterValues values, int substeps)
    {
        values.set(Param::Substeps, substeps);
        return values;
    }

    SimulationHost& m_host;
    const Clock::time_point m_epoch;
    std::unique_ptr<HairSimulation> m_sim; // null until the first groom succeeds
    Regions m_regions; // m_sim's regions, for regrooms
    std::shared_ptr<const GroomShape> m_groomShape; // of m_sim's groom, shared by its frames
    ParameterValues m_values; // what the running solver was given (as requested)
    ParameterValues m_groomedWith; // what m_sim's groom was built from
    std::optional<ParameterValues> m_refusedGroom;
    StyleEditsPtr m_style; // the artist's salon edits, for every groom
    std::vector<HairDryer> m_dryers;
    std::vector<HeldStrand> m_held; // the comb's strands while it drags
    SimulationHostPacer m_pacer;
    bool m_playing = false;
    std::uint64_t m_step = 0;
    std::uint64_t m_groomVersion = 0;
    double m_simulatedSeconds = 0.0; // since the groom or the last reset
    HeadMotion m_motion; // the document's, as last sent
    glm::vec3 m_pivotHead{ 0.0f }; // where m_sim's head turns (pivotOf)
    HeadPose m_headPose; // what the solver has now
    HeadPose m_easeFrom; // the pose when the motion last changed
    double m_easeStartSeconds = -kHeadEaseSeconds; // simulated time of that change
};

void SimulationHost::runLoop()
{
    Loop(*this).run();
}

} // namespace wisp
