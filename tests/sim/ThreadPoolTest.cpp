// The solver threads the editor's live simulation and its bake share one rule (issue 17): every
// core but one, which the GUI keeps, and never fewer than one.
#include "sim/util/ThreadPool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

using namespace wisp;

TEST(ThreadPool, SolverThreadsBesideTheGuiLeaveOneCoreAndNeverFewerThanOne)
{
    EXPECT_EQ(solverThreadsBesideGui(16), 15);
    EXPECT_EQ(solverThreadsBesideGui(2), 1);
    EXPECT_EQ(solverThreadsBesideGui(1), 1);
    EXPECT_EQ(solverThreadsBesideGui(0), 1); // hardware_concurrency() may not know
    EXPECT_EQ(solverThreadsBesideGui(), solverThreadsBesideGui(std::thread::hardware_concurrency()));
}

namespace {

// Runs `loops` loops back to back over `count` indices in chunks of `grain` and checks that each
// loop visits every index exactly once.
void expectEveryIndexOnceALoop(ThreadPool& pool, int loops, std::size_t count, std::size_t grain)
{
    std::vector<std::atomic<int>> visits(count);
    for (int loop = 0; loop < loops; ++loop) {
        pool.parallelFor(count, grain, [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i)
                visits[i].fetch_add(1, std::memory_order_relaxed);
        });
        // parallelFor returns only when every chunk has run: the counts are final here.
        for (std::size_t i = 0; i < count; ++i)
            ASSERT_EQ(visits[i].exchange(0), 1) << "loop " << loop << ", index " << i;
    }
}

} // namespace

TEST(ThreadPool, BackToBackLoopsVisitEveryIndexOnceWhileTheWorkersSpinBetweenThem)
{
    ThreadPool pool(2);
    expectEveryIndexOnceALoop(pool, 2000, 37, 1); // loops of a few microseconds: the workers spin between
    expectEveryIndexOnceALoop(pool, 200, 10000, 64);
    expectEveryIndexOnceALoop(pool, 200, 3, 4); // fewer indices than a chunk: the caller alone
}

TEST(ThreadPool, MoreThreadsThanCoresNeverSpinAndStillVisitEveryIndexOnce)
{
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    ThreadPool pool(cores + 2);
    ASSERT_EQ(pool.threadCount(), cores + 2);
    EXPECT_FALSE(pool.spins());
    expectEveryIndexOnceALoop(pool, 300, 101, 3);
    EXPECT_GE(pool.workerSleeps(), 1u);
}

TEST(ThreadPool, AWorkerThatWentToSleepIsWokenForTheNextLoop)
{
    ThreadPool pool(2);
    expectEveryIndexOnceALoop(pool, 1, 64, 1);
    // Nothing to do: the worker spins for kSpinMicroseconds, then sleeps. Wait (however slow the
    // machine) until it has, then give it a loop: it must be woken and the loop must finish.
    for (int wait = 0; pool.workerSleeps() == 0 && wait < 10000; ++wait)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ASSERT_GE(pool.workerSleeps(), 1u);
    const std::size_t sleepsBefore = pool.workerSleeps();
    std::atomic<int> ranOnWorker{ 0 };
    const std::thread::id caller = std::this_thread::get_id();
    for (int attempt = 0; attempt < 200 && ranOnWorker.load() == 0; ++attempt) {
        // Chunks that take a while, so the woken worker gets some of them.
        pool.parallelFor(8, 1, [&](std::size_t, std::size_t) {
            if (std::this_thread::get_id() != caller)
                ranOnWorker.fetch_add(1);
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        });
    }
    EXPECT_GT(ranOnWorker.load(), 0) << "the sleeping worker never took part";
    EXPECT_GE(pool.workerSleeps(), sleepsBefore);
    expectEveryIndexOnceALoop(pool, 50, 500, 7);
}

TEST(ThreadPool, APoolDestroyedWhileItsWorkersSpinOrSleepStopsThem)
{
    for (int i = 0; i < 50; ++i) {
        ThreadPool pool(2);
        expectEveryIndexOnceALoop(pool, 3, 16, 1);
        if (i % 2 == 1)
            std::this_thread::sleep_for(std::chrono::microseconds(200)); // past the spin: asleep, or near
    } // each destructor must join its worker (a hang here fails the suite's timeout)
}
