#pragma once
// sim/'s one pool of threads: the solver's parallel loops and the head's SDF bake
// (SignedDistanceField::bake, given the solver's pool by HairSimulation) run on it. Work is split
// into index ranges handed out as threads free (dynamic chunks, m_next); which thread runs which
// range never changes a result, because every range writes only its own data.
//
// Between loops a worker spins a little before it sleeps (kSpinMicroseconds), and so does the
// caller waiting for the workers: a solver step is one or a few loops a few tens of microseconds
// to milliseconds long, back to back, and waking a sleeping thread costs about as much as a small
// loop (a futex wake, and on a virtual machine the idle vCPU's halt and its wake-up interrupt:
// 20 to 60 µs on the development machines, where the 36,750-particle sphere's whole step is
// 180 µs). Only while the pool has no more threads than the machine has cores: spinning on a
// core another thread needs would slow that thread.

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace wisp {

// The solver threads for a simulation that runs beside an interactive window (the editor's live
// simulation and its bake): every core but one, which stays with the GUI so that drawing and input
// never queue behind the solver; at least one. `cores` as std::thread::hardware_concurrency()
// reports them (0: unknown).
// Thread: any.
inline int solverThreadsBesideGui(unsigned cores = std::thread::hardware_concurrency())
{
    return cores > 1 ? static_cast<int>(cores) - 1 : 1;
}

class ThreadPool {
public:
    // threadCount 0 means one thread per hardware core. The calling thread takes part in the work,
    // so a pool of N threads starts N - 1 workers (fewer, never a throw, when the system has no
    // more threads to give: threadCount() says how many it got).
    explicit ThreadPool(int threadCount = 0);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int threadCount() const { return static_cast<int>(m_workers.size()) + 1; }

    // How long a worker looks for the next loop before it sleeps, and the caller for the workers'
    // end before it sleeps.
    static constexpr int kSpinMicroseconds = 50;
    // Whether this pool spins at all (no more threads than cores).
    bool spins() const { return m_spins; }
    // How many times a worker has gone to sleep between loops since the pool started (a figure for
    // tests and benchmarks: back-to-back loops on idle cores should rarely need one).
    std::size_t workerSleeps() const { return m_workerSleeps.load(std::memory_order_relaxed); }

    // Calls body(begin, end) over [0, count) in chunks of `grain`, on all threads; returns when done.
    // body must not throw (a worker has nowhere to send it). Runs on the calling thread; not
    // reentrant, and one caller at a time.
    void parallelFor(std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body);

private:
    void workerLoop();
    void runChunks();
    // Spins until done() or kSpinMicroseconds have passed (at once when the pool does not spin);
    // returns done().
    template <class Done> bool spinUntil(const Done& done) const;

    std::vector<std::thread> m_workers;
    bool m_spins = false;
    std::mutex m_mutex;
    std::condition_variable m_wake;
    std::condition_variable m_done;
    // The loop: written by the caller before it publishes m_generation (release), read by the
    // workers after they see it (acquire), unchanged until every worker has left it (m_busyWorkers).
    const std::function<void(std::size_t, std::size_t)>* m_body = nullptr;
    std::size_t m_count = 0;
    std::size_t m_grain = 1;
    std::atomic<std::size_t> m_next{ 0 };
    std::atomic<std::size_t> m_generation{ 0 };
    std::atomic<int> m_busyWorkers{ 0 };
    std::atomic<bool> m_stopping{ false };
    int m_sleepingWorkers = 0; // under m_mutex
    bool m_callerSleeping = false; // under m_mutex
    std::atomic<std::size_t> m_workerSleeps{ 0 };
};

// body(begin, end) over [0, count): on `pool`, or on the calling thread when there is none.
inline void forRange(
    ThreadPool* pool, std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body)
{
    if (pool)
        pool->parallelFor(count, grain, body);
    else if (count > 0)
        body(0, count);
}

} // namespace wisp
