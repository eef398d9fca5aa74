// The solver threads the editor's live simulation and its bake share one rule (issue 17): every
// core but one, which the GUI keeps, and never fewer than one.
#include "sim/util/ThreadPool.h"

#include <gtest/gtest.h>

using namespace wisp;

TEST(ThreadPool, SolverThreadsBesideTheGuiLeaveOneCoreAndNeverFewerThanOne)
{
    EXPECT_EQ(solverThreadsBesideGui(16), 15);
    EXPECT_EQ(solverThreadsBesideGui(2), 1);
    EXPECT_EQ(solverThreadsBesideGui(1), 1);
    EXPECT_EQ(solverThreadsBesideGui(0), 1); // hardware_concurrency() may not know
    EXPECT_EQ(solverThreadsBesideGui(), solverThreadsBesideGui(std::thread::hardware_concurrency()));
}
