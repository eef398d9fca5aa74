#pragma once
// sim/'s one pool of threads: the solver's parallel loops and the head's SDF bake
// (SignedDistanceField::bake, given the solver's pool by HairSimulation) run on it. Work is split
// into index ranges handed out as threads free (dynamic chunks, m_next); which thread runs which
// range never changes a result, because every range writes only its own data.

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

    // Calls body(begin, end) over [0, count) in chunks of `grain`, on all threads; returns when done.
    // body must not throw (a worker has nowhere to send it). Runs on the calling thread; not
    // reentrant, and one caller at a time.
    void parallelFor(std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body);

private:
    void workerLoop();
    void runChunks();

    std::vector<std::thread> m_workers;
    std::mutex m_mutex;
    std::condition_variable m_wake;
    std::condition_variable m_done;
    const std::function<void(std::size_t, std::size_t)>* m_body = nullptr;
    std::size_t m_count = 0;
    std::size_t m_grain = 1;
    std::atomic<std::size_t> m_next{ 0 };
    std::size_t m_generation = 0;
    int m_busyWorkers = 0;
    bool m_stopping = false;
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
