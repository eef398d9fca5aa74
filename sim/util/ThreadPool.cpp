#include "sim/util/ThreadPool.h"

#include "sim/util/ThreadName.h"

#include <algorithm>
#include <chrono>

namespace wisp {

namespace {

// A hint to the core that this thread is spinning (x86's pause, Arm's yield): it frees the
// core's resources for a sibling hyperthread and eases the exit from the loop.
inline void spinPause()
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__) || defined(__arm__)
    asm volatile("yield");
#endif
}

} // namespace

ThreadPool::ThreadPool(int threadCount)
{
    const int cores = static_cast<int>(std::thread::hardware_concurrency());
    if (threadCount <= 0)
        threadCount = std::max(1, cores);
    // (Before the workers start: they read it.)
    m_spins = cores > 0 && threadCount <= cores;
    try {
        m_workers.reserve(static_cast<std::size_t>(threadCount - 1));
        for (int i = 1; i < threadCount; ++i)
            m_workers.emplace_back([this] {
                nameThisThread("wisp-solver");
                workerLoop();
            });
    } catch (...) {
        // No more threads (or memory) to be had: the workers started and the caller do the work,
        // rather than a throw out of sim/ with threads left running (std::terminate).
    }
}

ThreadPool::~ThreadPool()
{
    {
        std::lock_guard lock(m_mutex);
        m_stopping.store(true, std::memory_order_relaxed);
    }
    m_wake.notify_all();
    for (std::thread& t : m_workers)
        t.join();
}

template <class Done> bool ThreadPool::spinUntil(const Done& done) const
{
    if (done())
        return true;
    if (!m_spins)
        return false;
    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(kSpinMicroseconds);
    for (;;) {
        // The clock every few pauses (a pause is 10 to 150 cycles, the clock's read about 20 ns).
        for (int i = 0; i < 16; ++i) {
            spinPause();
            if (done())
                return true;
        }
        if (std::chrono::steady_clock::now() >= until)
            return done();
    }
}

void ThreadPool::runChunks()
{
    for (;;) {
        const std::size_t begin = m_next.fetch_add(m_grain, std::memory_order_relaxed);
        if (begin >= m_count)
            return;
        (*m_body)(begin, std::min(m_count, begin + m_grain));
    }
}

void ThreadPool::workerLoop()
{
    std::size_t seen = 0;
    auto published = [&] {
        return m_stopping.load(std::memory_order_relaxed) || m_generation.load(std::memory_order_acquire) != seen;
    };
    for (;;) {
        if (!spinUntil(published)) {
            // Asleep until the caller publishes a loop: it looks at m_sleepingWorkers under the
            // mutex after it publishes, so a worker that counted itself before that is woken, and
            // one that comes after sees the new generation in wait()'s test, under the same mutex.
            std::unique_lock lock(m_mutex);
            ++m_sleepingWorkers;
            m_workerSleeps.fetch_add(1, std::memory_order_relaxed);
            m_wake.wait(lock, published);
            --m_sleepingWorkers;
        }
        if (m_stopping.load(std::memory_order_relaxed))
            return;
        seen = m_generation.load(std::memory_order_acquire);
        runChunks();
        if (m_busyWorkers.fetch_sub(1, std::memory_order_acq_rel) == 1) {
            // The last worker out: wake the caller if it went to sleep (under the mutex, so a
            // caller about to wait has either seen the count at zero or is waiting).
            std::lock_guard lock(m_mutex);
            if (m_callerSleeping)
                m_done.notify_one();
        }
    }
}

void ThreadPool::parallelFor(
    std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body)
{
    if (count == 0)
        return;
    grain = std::max<std::size_t>(1, grain);
    if (m_workers.empty() || count <= grain) {
        body(0, count);
        return;
    }
    bool wake = false;
    {
        std::lock_guard lock(m_mutex);
        m_body = &body;
        m_count = count;
        m_grain = grain;
        m_next.store(0, std::memory_order_relaxed);
        m_busyWorkers.store(static_cast<int>(m_workers.size()), std::memory_order_relaxed);
        m_generation.fetch_add(1, std::memory_order_release);
        wake = m_sleepingWorkers > 0;
    }
    if (wake)
        m_wake.notify_all();
    runChunks();
    auto finished = [&] { return m_busyWorkers.load(std::memory_order_acquire) == 0; };
    if (!spinUntil(finished)) {
        std::unique_lock lock(m_mutex);
        m_callerSleeping = true;
        m_done.wait(lock, finished);
        m_callerSleeping = false;
    }
    m_body = nullptr;
}

} // namespace wisp
