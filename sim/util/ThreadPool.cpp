#include "sim/util/ThreadPool.h"

#include "sim/util/ThreadName.h"

#include <algorithm>

namespace wisp {

ThreadPool::ThreadPool(int threadCount)
{
    if (threadCount <= 0)
        threadCount = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
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
        m_stopping = true;
    }
    m_wake.notify_all();
    for (std::thread& t : m_workers)
        t.join();
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
    for (;;) {
        {
            std::unique_lock lock(m_mutex);
            m_wake.wait(lock, [&] { return m_stopping || m_generation != seen; });
            if (m_stopping)
                return;
            seen = m_generation;
        }
        runChunks();
        {
            std::lock_guard lock(m_mutex);
            if (--m_busyWorkers == 0)
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
    {
        std::lock_guard lock(m_mutex);
        m_body = &body;
        m_count = count;
        m_grain = grain;
        m_next.store(0, std::memory_order_relaxed);
        m_busyWorkers = static_cast<int>(m_workers.size());
        ++m_generation;
    }
    m_wake.notify_all();
    runChunks();
    std::unique_lock lock(m_mutex);
    m_done.wait(lock, [&] { return m_busyWorkers == 0; });
    m_body = nullptr;
}

} // namespace wisp
