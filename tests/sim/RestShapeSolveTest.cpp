// The combed rest-shape solve (sim/RestShapeSolve.*): strands are solved independently, so one
// that cannot be held must not leave the others half solved.
#include "sim/RestShapeSolve.h"
#include "sim/HairCurves.h"
#include "sim/SolverSettings.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <vector>

using namespace wisp;

namespace {

// A lock combed straight out sideways from `root` (+x), 20 cm in 16 segments.
void addSidewaysLock(HairCurves& curves, const glm::vec3& root)
{
    constexpr int kSegments = 16;
    const std::size_t s = curves.addStrand(kSegments + 1);
    const auto points = curves.strandForWrite(s);
    for (int j = 0; j <= kSegments; ++j)
        points[static_cast<std::size_t>(j)] = root + glm::vec3(0.2f * static_cast<float>(j) / kSegments, 0.0f, 0.0f);
}

} // namespace

// Before: refinement stopped for every strand as soon as the worst gap stopped shrinking, so a
// limp strand combed with stiff ones (a comb catching a wisp too soft to hold) left the stiff ones
// at the first, unrefined estimate: the whole combed lock sagged back in the editor.
TEST(RestShapeSolve, AStrandThatCannotBeHeldDoesNotStopTheOthersConverging)
{
    SolverSettings settings;
    settings.substeps = 2;
    settings.stiffness = 0.6f;
    settings.dampingPerSecond = 1.0f;

    HairCurves alone;
    addSidewaysLock(alone, glm::vec3(0.0f));
    const std::vector<float> stiff{ 1.0f };
    const RestShapeSolution held = solveRestShapes(alone, stiff, settings, nullptr);
    ASSERT_GT(held.iterations, 1) << "the stiff lock needed no refinement: the test proves nothing";

    HairCurves both;
    addSidewaysLock(both, glm::vec3(0.0f));
    addSidewaysLock(both, glm::vec3(0.0f, 0.0f, 0.3f));
    const std::vector<float> scales{ 1.0f, 0.0f }; // the second is limp: no rest shape holds it sideways
    const RestShapeSolution mixed = solveRestShapes(both, scales, settings, nullptr);
    EXPECT_GT(mixed.worstGapMetres, 0.05f) << "the limp strand was held: the test proves nothing";

    float difference = 0.0f;
    const auto a = held.rest.strand(0);
    const auto b = mixed.rest.strand(0);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t j = 0; j < a.size(); ++j)
        difference = std::max(difference, glm::distance(a[j], b[j]));
    EXPECT_LT(difference, 1e-4f) << "the stiff lock's rest shape depends on the limp strand beside it";
    EXPECT_LT(held.worstGapMetres, 0.01f) << "a stiff lock combed sideways is not held within 1 cm";
}
