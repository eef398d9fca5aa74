#include "app/editor/BakeController.h"

#include "app/editor/Document.h"
#include "app/editor/SettledScene.h"
#include "sim/solver/HairSimulation.h"
#include "sim/style/BrushContext.h"
#include "sim/util/ThreadName.h"
#include "sim/util/ThreadPool.h"

#include <QMetaObject>

#include <algorithm>
#include <chrono>
#include <exception>
#include <string>
#include <utility>

namespace wisp {

namespace {

// What the worker needs from the document, copied on the GUI thread when the bake starts.
struct BakeInput {
    HeadModelPtr head;
    std::vector<GrowthRegion> regions;
    std::uint32_t soloId = kNoSolo;
    ParameterValues values;
    StyleEditsPtr style;
    HeadMotion motion;
};

struct BakeOutcome {
    std::shared_ptr<BakedScene> baked; // set on success
    std::string error;
    bool cancelled = false;
};

// Thread: the bake's worker. Grooms a simulation of its own and bakes it.
BakeOutcome runBake(const BakeInput& in, BakeOptions options)
{
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    Clock::time_point afterFrameOne = start;
    options.progress = [&afterFrameOne, report = std::move(options.progress)](int done, int total) {
        if (done == 1)
            afterFrameOne = Clock::now();
        report(done, total);
    };
    BakeOutcome out;
    try {
        HairSimulation sim(solverThreadsBesideGui()); // as the live simulation: one core for the GUI
        if (in.style)
            sim.setStyle(in.style);
        out.error = sim.setup(in.head, in.regions, in.soloId, in.values);
        if (out.error.empty())
            out.error = sim.applyForces(in.values);
        if (!out.error.empty())
            return out;
        BakeResult result = bakeMotion(sim, in.motion, pivotOf(sim.head()), options);
        if (result.cancelled) {
            out.cancelled = true;
            return out;
        }
        if (!result.error.empty()) {
            out.error = std::move(result.error);
            return out;
        }
        auto baked = std::make_shared<BakedScene>();
        fillFrame(sim, in.values, baked->look);
        baked->look.strands = {};
        baked->look.groomShape = groomShapeOf(sim);
        baked->look.wetness.clear(); // each cached frame has its own (BakedFrame::wetness)
        baked->cache = std::move(result.cache);
        baked->head = sim.headModel();
        const Clock::time_point end = Clock::now();
        baked->drapeMilliseconds = std::chrono::duration<double, std::milli>(afterFrameOne - start).count();
        if (options.range.lastFrame > 1)
            baked->millisecondsPerFrame = std::chrono::duration<double, std::milli>(end - afterFrameOne).count()
                / (options.range.lastFrame - 1);
        out.baked = std::move(baked);
    } catch (const std::exception& e) {
        out.error = std::string("bake: ") + e.what(); // sim/ does not throw, but memory can run out
    }
    return out;
}

} // namespace

BakeController::BakeController(QObject* parent)
    : QObject(parent)
{
}

BakeController::~BakeController()
{
    m_cancel = true;
    join();
}

void BakeController::join()
{
    if (m_thread.joinable())
        m_thread.join();
}

QString BakeController::start(const Document& document)
{
    if (isRunning())
        return tr("a bake is already running");
    if (const std::string e = validateBakeRange(document.timeline()); !e.empty())
        return QString::fromStdString(e);
    join(); // the last worker has posted its end; it is gone or about to be
    BakeInput in{ document.headModel(), document.regions(), document.soloRegion(), document.parameters(),
        document.style(), document.headMotion() };
    BakeOptions options;
    options.range = document.timeline();
    options.memoryBoundBytes = m_memoryBoundBytes;
    options.cancelled = [this] { return m_cancel.load(); };
    options.progress = [this](int done, int total) {
        m_workerFrames = done;
        QMetaObject::invokeMethod(
            this,
            [this, done, total] {
                m_framesDone = done;
                emit progress(done, total);
            },
            Qt::QueuedConnection);
    };
    m_cancel = false;
    m_finished = false;
    m_framesDone = 0;
    m_workerFrames = 0;
    m_workerFramesAtCancel = 0;
    m_thread = std::thread([this, in = std::move(in), options = std::move(options)] {
        nameThisThread("wisp-bake");
        BakeOutcome outcome = runBake(in, options);
        // The last thing the worker does: the GUI thread joins it when this arrives.
        QMetaObject::invokeMethod(
            this,
            [this, outcome = std::move(outcome)] {
                m_finished = true;
                join();
                if (outcome.baked) {
                    m_baked = outcome.baked;
                    emit finished();
                } else if (outcome.cancelled) {
                    emit cancelled();
                } else {
                    emit failed(QString::fromStdString(outcome.error));
                }
            },
            Qt::QueuedConnection);
    });
    return {};
}

void BakeController::cancel()
{
    m_workerFramesAtCancel = m_workerFrames.load();
    m_cancel = true;
}

FramePtr BakeController::frameAt(int frame) const
{
    if (!m_baked)
        return nullptr;
    const BakedFrame* baked = m_baked->cache.find(frame);
    if (!baked)
        return nullptr;
    auto out = std::make_shared<Frame>(m_baked->look);
    out->strands.offsets = m_baked->cache.offsets;
    out->strands.positions = baked->positions;
    out->wetness = baked->wetness; // wet hair scrubs wet, drying as it did in the bake
    out->headToWorld = baked->headToWorld; // the viewport draws the head where the bake had it
    out->step = static_cast<std::uint64_t>(frame - 1) * static_cast<std::uint64_t>(m_baked->cache.stepsPerFrame);
    out->simulatedSeconds = m_baked->cache.range.secondsOf(frame);
    return out;
}

} // namespace wisp
