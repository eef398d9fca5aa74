#include "app/editor/SimulationHost.h"

#include "sim/util/ThreadName.h"
#include "sim/util/ThreadPool.h"

#include <QMetaObject>

#include <algorithm>
#include <utility>

namespace wisp {

SimulationHost::SimulationHost(QObject* parent)
    : SimulationHost(SecondsClock{}, parent)
{
}

SimulationHost::SimulationHost(SecondsClock clock, QObject* parent)
    : QObject(parent)
    , m_solverThreads(solverThreadsBesideGui())
    , m_clock(std::move(clock))
{
    m_thread = std::thread([this] {
        nameThisThread("wisp-sim");
        runLoop();
    });
}

SimulationHost::~SimulationHost()
{
    {
        std::lock_guard lock(m_mutex);
        m_inbox.stopping = true;
    }
    m_wake.notify_all();
    if (m_thread.joinable())
        m_thread.join();
    // Frame and error signals still queued for this object are dropped by ~QObject.
}

void SimulationHost::setScene(TriangleMesh head, std::vector<float> growthWeights, ParameterValues values)
{
    GrowthRegion region;
    region.name = "growth map";
    region.weights = std::move(growthWeights);
    region.values = values;
    postScene(Scene{ nullptr, std::move(head), Regions{ { std::move(region) }, kNoSolo, true }, std::move(values) });
}

void SimulationHost::setScene(
    TriangleMesh head, std::vector<GrowthRegion> regions, std::uint32_t soloId, ParameterValues values)
{
    postScene(Scene{ nullptr, std::move(head), Regions{ std::move(regions), soloId, false }, std::move(values) });
}

void SimulationHost::setScene(
    HeadModelPtr head, std::vector<GrowthRegion> regions, std::uint32_t soloId, ParameterValues values)
{
    postScene(Scene{ std::move(head), {}, Regions{ std::move(regions), soloId, false }, std::move(values) });
}

// A new scene replaces any the simulation thread has not taken yet, and the parameters and regions
// waiting beside it (the scene's are newer).
void SimulationHost::postScene(Scene scene)
{
    std::optional<Scene> superseded; // freed after unlocking: the simulation thread never waits on a free
    {
        std::lock_guard lock(m_mutex);
        superseded = std::exchange(m_inbox.scene, std::move(scene));
        m_inbox.parameters.reset();
        m_inbox.regions.reset();
    }
    m_wake.notify_one();
}

void SimulationHost::setRegions(std::vector<GrowthRegion> regions, std::uint32_t soloId)
{
    std::optional<Regions> superseded;
    {
        std::lock_guard lock(m_mutex);
        if (m_inbox.scene) { // folded into the scene still waiting
            m_inbox.scene->regions = Regions{ std::move(regions), soloId, false };
        } else {
            superseded = std::exchange(m_inbox.regions, Regions{ std::move(regions), soloId, false });
        }
    }
    m_wake.notify_one();
}

void SimulationHost::setParameters(const ParameterValues& values)
{
    {
        std::lock_guard lock(m_mutex);
        // Folded into a scene still waiting: one groom with the newest values instead of two.
        if (m_inbox.scene)
            m_inbox.scene->values = values;
        else
            m_inbox.parameters = values;
    }
    m_wake.notify_one();
}

void SimulationHost::play()
{
    {
        std::lock_guard lock(m_mutex);
        if (m_inbox.playing)
            return;
        m_inbox.playing = true;
        m_playing.store(true);
    }
    m_wake.notify_one();
    emit playingChanged(true);
}

void SimulationHost::pause()
{
    {
        std::lock_guard lock(m_mutex);
        if (!m_inbox.playing)
            return;
        m_inbox.playing = false;
        m_playing.store(false);
    }
    m_wake.notify_one();
    emit playingChanged(false);
}

bool SimulationHost::isPlaying() const
{
    return m_playing.load();
}

void SimulationHost::stepOnce()
{
    {
        std::lock_guard lock(m_mutex);
        if (m_inbox.playing)
            return;
        m_inbox.actions.push_back(Action::Step);
    }
    m_wake.notify_one();
}

void SimulationHost::resetToRest()
{
    {
        std::lock_guard lock(m_mutex);
        m_inbox.actions.push_back(Action::Reset);
    }
    m_wake.notify_one();
}

void SimulationHost::setStyle(StyleEditsPtr style)
{
    std::optional<StyleEditsPtr> superseded;
    {
        std::lock_guard lock(m_mutex);
        superseded = std::exchange(m_inbox.style, std::move(style));
    }
    m_wake.notify_one();
}

void SimulationHost::setDryers(std::vector<HairDryer> dryers)
{
    std::optional<std::vector<HairDryer>> superseded;
    {
        std::lock_guard lock(m_mutex);
        superseded = std::exchange(m_inbox.dryers, std::move(dryers));
    }
    m_wake.notify_one();
}

void SimulationHost::holdStrands(std::vector<HeldStrand> held)
{
    std::optional<std::vector<HeldStrand>> superseded;
    {
        std::lock_guard lock(m_mutex);
        superseded = std::exchange(m_inbox.held, std::move(held));
    }
    m_wake.notify_one();
}

void SimulationHost::wetStrands(std::vector<std::uint64_t> keyIdentities, float wetness)
{
    {
        std::lock_guard lock(m_mutex);
        m_inbox.wettings.push_back({ std::move(keyIdentities), wetness });
    }
    m_wake.notify_one();
}

void SimulationHost::setHeadMotion(HeadMotion motion)
{
    std::optional<HeadMotion> superseded;
    {
        std::lock_guard lock(m_mutex);
        superseded = std::exchange(m_inbox.motion, std::move(motion));
    }
    m_wake.notify_one();
}

FramePtr SimulationHost::latestFrame() const
{
    return m_latest.load();
}

std::uint64_t SimulationHost::publishedFrames() const
{
    return m_published.load();
}

std::uint64_t SimulationHost::loopWakeups() const
{
    return m_loopWakeups.load();
}

bool SimulationHost::isIdle() const
{
    std::lock_guard lock(m_mutex);
    // The thread sleeps paused (its own playing is false) and nothing was asked since.
    return m_idle.load() && !m_inbox.hasRequests(false);
}

int SimulationHost::effectiveSubsteps() const
{
    return m_effectiveSubsteps.load();
}

void SimulationHost::publish(FramePtr frame)
{
    m_latest.store(std::move(frame));
    m_published.fetch_add(1);
    // One pending signal at most: a GUI busy for several frames is told once and draws the newest.
    if (!m_frameSignalPending.exchange(true)) {
        QMetaObject::invokeMethod(
            this,
            [this] {
                m_frameSignalPending.store(false); // before emitting: a frame published meanwhile signals again
                emit frameReady();
            },
            Qt::QueuedConnection);
    }
}

void SimulationHost::postError(const std::string& message)
{
    QMetaObject::invokeMethod(
        this, [this, text = QString::fromStdString(message)] { emit errorOccurred(text); }, Qt::QueuedConnection);
}

void SimulationHost::postSceneReady()
{
    QMetaObject::invokeMethod(
        this, [this] { emit sceneReady(); }, Qt::QueuedConnection);
}

} // namespace wisp
