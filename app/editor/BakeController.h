#pragma once
// The editor's bake: the document's scene simulated over its timeline range into an in-memory
// cache (sim/motion/HairBake.h) on a worker thread of its own, so the window keeps drawing and the
// live simulation keeps its own state. One bake at a time.
//
// - Start takes a snapshot of the document (head, regions, parameters, style, head motion, range):
//   edits made during the bake do not reach it (the timeline dock marks such a cache stale).
// - Cancel is asked between solver steps (and during the drape), so a bake stops within one step.
//   A cancelled or refused bake leaves no cache of its own: the previous cache, if any, stays.
// - The memory bound (kDefaultBakeMemoryBytes) refuses a range whose frames would not fit before
//   any step runs; failed() carries the bake's message.
//
// Thread: the object lives on the GUI thread and every public function runs there; the worker
// posts its progress and result back as queued calls.

#include "sim/geometry/HeadModel.h"
#include "sim/motion/HairBake.h"
#include "sim/solver/Frame.h"

#include <QObject>
#include <QString>

#include <atomic>
#include <cstddef>
#include <memory>
#include <thread>

namespace wisp {

class Document;

// A finished bake and what its frames are drawn with: the looks and groom shape of the baked
// groom (the same for every frame), so a cached frame is drawn as a live one is.
struct BakedScene {
    BakeCache cache;
    Frame look; // strands empty; everything else as the bake's last frame had it
    // Wall clock, for the dock's status and the README (never for decisions): the groom and drape
    // up to frame 1, then each later frame (its solver steps and its drawn frame).
    double drapeMilliseconds = 0.0;
    double millisecondsPerFrame = 0.0;
    HeadModelPtr head; // the head it was baked on (head space), for exports
};
using BakedScenePtr = std::shared_ptr<const BakedScene>;

class BakeController : public QObject {
    Q_OBJECT
public:
    explicit BakeController(QObject* parent = nullptr);
    ~BakeController() override; // cancels a running bake and waits for it (within one step)

    // Starts baking the document's timeline range. Returns the refusal (a bake already running, an
    // invalid range) without starting; empty when started.
    QString start(const Document& document);
    void cancel();
    bool isRunning() const { return m_thread.joinable() && !m_finished; }

    // The last finished bake; null before one.
    const BakedScenePtr& baked() const { return m_baked; }
    // Frame `frame` of the last bake as the viewport draws it: the baked positions exactly; null
    // when that frame was not baked.
    FramePtr frameAt(int frame) const;

    // The bake's memory bound (bytes of kept frames); tests lower it to see the refusal.
    void setMemoryBoundBytes(std::size_t bytes) { m_memoryBoundBytes = bytes; }
    std::size_t memoryBoundBytes() const { return m_memoryBoundBytes; }
    // Simulated frames of the running (or last) bake, pre-roll included, as progress() said.
    int framesDone() const { return m_framesDone; }
    // Frames the worker finished after cancel() was called (read once the bake has ended): how
    // promptly Cancel stops it, counted on the worker's side, not by progress reports in flight.
    int framesFinishedAfterCancel() const { return m_workerFrames.load() - m_workerFramesAtCancel.load(); }

signals:
    void progress(int framesDone, int framesTotal);
    void finished(); // baked() holds the new bake
    void failed(const QString& message); // refused or went wrong; nothing changed
    void cancelled(); // stopped by cancel(); nothing changed

private:
    void join();

    std::thread m_thread;
    std::atomic<bool> m_cancel{ false };
    bool m_finished = true; // the worker has posted its end (GUI thread's view)
    int m_framesDone = 0;
    std::atomic<int> m_workerFrames{ 0 }; // written by the worker as each frame ends
    std::atomic<int> m_workerFramesAtCancel{ 0 };
    std::size_t m_memoryBoundBytes = kDefaultBakeMemoryBytes;
    BakedScenePtr m_baked;
};

} // namespace wisp
