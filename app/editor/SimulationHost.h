#pragma once
// The editor's simulation thread. It owns the HairSimulation (groom, collider, solver) and is the
// only thread that touches it; the GUI thread talks to it through queued messages and reads back
// immutable frames, so the GUI never waits for the solver (see DESIGN.md, "Shape of the program").
//
// - Messages: setScene, setParameters, play/pause, stepOnce and resetToRest only record a request
//   under a mutex held for a few pointer moves and wake the thread. Scene and parameters coalesce:
//   only the newest of each matters, and parameters sent while a scene is still waiting are folded
//   into that scene (one groom, not two).
// - Pace: while playing, one step per time_step of wall clock, on a fixed cadence, sleeping on a
//   condition variable in between (never spinning). A solver that cannot keep up is not chased:
//   frames say fallingBehind with timeScale < 1 (slow motion), and if that persists the substeps
//   are lowered (never below 1) until a step fits, then given back once there is headroom; frames
//   keep saying fallingBehind while fewer substeps than requested run (SimulationHostPacer.h).
// - Frames: a new Frame per step (and after a groom, a reset or stepOnce), published by swapping
//   one atomic shared_ptr; nothing writes a frame after that.
// - Regroom (a new scene, or a change of a Groom-group parameter or of simulate_all_strands) runs
//   on the simulation thread into a new HairSimulation: the previous frame stays visible meanwhile,
//   and a refused groom leaves the previous scene running (errorOccurred says why).
//
// Thread: the object lives on the GUI thread; each function says where it runs.

#include "sim/geometry/HeadModel.h"
#include "sim/geometry/TriangleMesh.h"
#include "sim/groom/GrowthRegion.h"
#include "sim/motion/HeadMotion.h"
#include "sim/params/Parameters.h"
#include "sim/solver/Frame.h"
#include "sim/style/HairDryer.h"
#include "sim/style/StyleEdits.h"

#include <QObject>
#include <QString>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace wisp {

class SimulationHost : public QObject {
    Q_OBJECT
public:
    // The pacer's clock: seconds on any fixed origin, read only by the simulation thread. The
    // default is the steady clock; tests pass a clock they move themselves, so that step costs,
    // slow motion and substep shedding are decided by numbers the test chose, not by how busy the
    // machine is. Thread: simulation (the function is called there, and must be safe to call there).
    using SecondsClock = std::function<double()>;

    // Thread: GUI. Starts the simulation thread, idle until the first scene arrives.
    explicit SimulationHost(QObject* parent = nullptr);
    // Thread: GUI. As above, paced by `clock` instead of the steady clock (see SecondsClock).
    // With such a clock the simulation thread cannot sleep until a step is due, so while playing
    // it looks at the clock every kInjectedClockPollMs of real time.
    SimulationHost(SecondsClock clock, QObject* parent = nullptr);
    static constexpr int kInjectedClockPollMs = 1;
    // Thread: GUI. Stops and joins the simulation thread: at once when it is waiting or stepping,
    // after the groom when it is regrooming (a default-scene groom takes a fraction of a second);
    // queued work that has not started is dropped.
    ~SimulationHost() override;

    // Thread: GUI; returns at once. Grooms `head` where `growthWeights` allow (one weight per vertex)
    // with `values`, on the simulation thread; sceneReady and a step-0 frame of the hair hanging at
    // rest (draped under gravity, playing or paused) follow, or errorOccurred and the previous
    // scene keeps running.
    void setScene(TriangleMesh head, std::vector<float> growthWeights, ParameterValues values);
    // The editor's scene: `head` grown by its regions (see growingRegions for soloId).
    void setScene(TriangleMesh head, std::vector<GrowthRegion> regions, std::uint32_t soloId, ParameterValues values);
    // The same on the document's head model (its BVH is shared, not built again).
    void setScene(HeadModelPtr head, std::vector<GrowthRegion> regions, std::uint32_t soloId, ParameterValues values);
    // Thread: GUI; returns at once. New regions for the running head (a brush dab, a wisp slider, a
    // region shown or hidden): regroomed on the simulation thread while the hair keeps moving; the
    // strands that still exist keep their motion, new ones start at rest. Only the newest matters.
    void setRegions(std::vector<GrowthRegion> regions, std::uint32_t soloId);
    // Thread: GUI; returns at once. Forces and solver parameters apply from the next step; a change
    // of any Groom-group parameter or of simulate_all_strands regrooms on the simulation thread
    // (the previous frame stays visible meanwhile). A groom refused once is not retried until its
    // groom parameters change again.
    void setParameters(const ParameterValues& values);
    // --- The head's motion (HeadMotion.h) ----------------------------------------------------------
    // Thread: GUI; returns at once. From the next step the solver's head follows `motion` at the
    // simulated time (the clock starts at 0 with each scene and each reset, and runs while playing
    // or stepping; keys play once and then hold, procedural motions repeat). A new motion does not
    // teleport the head: it eases from where the head is to the new motion's pose over
    // kHeadEaseSeconds of simulated time (smoothstep, so the roots' velocity stays continuous and
    // no impulse flings the hair). Only the newest matters.
    void setHeadMotion(HeadMotion motion);
    static constexpr double kHeadEaseSeconds = 0.15;

    // --- Styling on live hair (StyleEdits.h) -------------------------------------------------------
    // Thread: GUI; returns at once. The artist's salon edits: the running hair is regroomed with
    // them (combed strands get a solved rest shape, so this can take a little longer), and every
    // later scene is groomed with them. Only the newest matters.
    void setStyle(StyleEditsPtr style);
    // Thread: GUI; returns at once. The blow-dryers while the artist holds one (two with X
    // symmetry); an empty list puts them down.
    void setDryers(std::vector<HairDryer> dryers);
    // A simulated strand held where the comb drags it: identity (Groom::strandIdentity) and
    // positions, world space, root first, as many as the strand has.
    struct HeldStrand {
        std::uint64_t identity = 0;
        std::vector<glm::vec3> positions;
    };
    // Thread: GUI; returns at once. Holds these strands at rest where given after every step until
    // the next call (an empty list lets go). While paused, a frame shows them at once.
    void holdStrands(std::vector<HeldStrand> held);
    // Thread: GUI; returns at once. The wet brush: the wisps whose key hairs have these identities
    // become at least this wet (0..1) now, and dry from there. Live only: the document keeps what
    // the brush applied.
    void wetStrands(std::vector<std::uint64_t> keyIdentities, float wetness);

    // Thread: GUI. Start and stop stepping in real time; playingChanged follows a change at once.
    // A step already running when pause() is called still publishes its frame; none after it.
    void play();
    void pause();
    // Thread: any.
    bool isPlaying() const;
    // Thread: GUI. One step while paused (ignored while playing), published as one frame.
    void stepOnce();
    // Thread: GUI. Every particle back at rest, step 0, published as one frame; playing continues
    // from rest if it was playing. "Rest" is the hair as it hangs at rest: the groom's rest shape
    // settled under gravity alone on the simulation thread (HairSimulation::drapeAtRest), as a new
    // scene starts; the GUI does not wait for it.
    void resetToRest();

    // Thread: any. The newest published frame, null before the first groom; copies one pointer
    // (std::atomic<std::shared_ptr>), never waits for the solver.
    FramePtr latestFrame() const;
    // Thread: any. Frames published since construction.
    std::uint64_t publishedFrames() const;
    // Thread: any. Times the simulation thread has woken (to take requests or to step) since
    // construction. A paused host with nothing asked of it sleeps on a condition variable and adds
    // none, however long it is left: what a test counts instead of timing the processor.
    std::uint64_t loopWakeups() const;
    // Thread: any. Whether the simulation thread sleeps with nothing to do: paused (or no scene),
    // every request taken and done, no step running. What a test waits for after pause() instead of
    // a fixed delay: a step that was running when pause() came has published its frame by then
    // (the sanitizer build's steps take longer than any delay that is short in the Release build).
    bool isIdle() const;
    // Thread: any. Substeps the solver runs now: the requested substeps, or fewer while the machine
    // cannot keep real time (0 before the first groom).
    int effectiveSubsteps() const;
    // Thread: any. Threads the solver uses: one per core less one kept for the GUI, at least 1.
    int solverThreadCount() const { return m_solverThreads; }

signals:
    // Delivered on the GUI thread: the simulation thread posts one queued call per frame unless one
    // is already pending, so a slow GUI gets one signal for many frames and reads latestFrame().
    // (Receivers may still connect with Qt::QueuedConnection; it only adds one event-loop turn.)
    void frameReady();
    // Emitted on the GUI thread from play() and pause().
    void playingChanged(bool playing);
    // Delivered on the GUI thread: a refused groom or parameter set; the previous state keeps running.
    void errorOccurred(const QString& message);
    // Delivered on the GUI thread after a (re)groom completed and its step-0 frame was published.
    void sceneReady();

private:
    class Loop;
    friend class Loop;

    // Thread: simulation. Runs the Loop (SimulationHostLoop.cpp) until the host stops.
    void runLoop();

    struct Regions {
        std::vector<GrowthRegion> regions;
        std::uint32_t soloId = kNoSolo;
        // A scene given by one growth map: its one region takes the Wisp-group values of every
        // parameter set (the CLI's and the tests' way), and an empty map is an error.
        bool fromParameters = false;
    };
    struct Scene {
        HeadModelPtr head; // null: built from `mesh` on the simulation thread
        TriangleMesh mesh;
        Regions regions;
        ParameterValues values;
    };
    enum class Action { Step, Reset };
    void postScene(Scene scene);
    struct Wetting {
        std::vector<std::uint64_t> keyIdentities;
        float wetness = 0.0f;
    };
    // Requests from the GUI thread not yet taken by the simulation thread (guarded by m_mutex).
    struct Inbox {
        std::optional<Scene> scene;
        std::optional<ParameterValues> parameters;
        std::optional<Regions> regions;
        std::vector<Action> actions; // in the order asked
        std::optional<StyleEditsPtr> style;
        std::optional<std::vector<HairDryer>> dryers; // set: a change (to dryers or to none)
        std::optional<std::vector<HeldStrand>> held;
        std::vector<Wetting> wettings;
        std::optional<HeadMotion> motion;
        bool playing = false;
        bool stopping = false;
        // Something for a simulation thread that plays (`playing`) or not to take.
        bool hasRequests(bool threadPlaying) const
        {
            return stopping || scene || parameters || regions || !actions.empty() || style || dryers || held
                || !wettings.empty() || motion || playing != threadPlaying;
        }
    };

    // Thread: simulation.
    void publish(FramePtr frame);
    void postError(const std::string& message);
    void postSceneReady();

    const int m_solverThreads;
    const SecondsClock m_clock; // empty: the steady clock
    mutable std::mutex m_mutex;
    std::condition_variable m_wake;
    Inbox m_inbox;

    std::atomic<bool> m_playing{ false }; // mirrors m_inbox.playing for lock-free reads
    std::atomic<std::shared_ptr<const Frame>> m_latest;
    std::atomic<std::uint64_t> m_published{ 0 };
    std::atomic<std::uint64_t> m_loopWakeups{ 0 };
    std::atomic<bool> m_idle{ false }; // isIdle(): set by the simulation thread
    std::atomic<bool> m_frameSignalPending{ false };
    std::atomic<int> m_effectiveSubsteps{ 0 };

    std::thread m_thread; // last: started once everything it reads exists
};

} // namespace wisp
