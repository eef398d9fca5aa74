// The combed rest-shape solve (sim/solver/RestShapeSolve.*): strands are solved independently, so one
// that cannot be held must not leave the others half solved.
#include "sim/solver/RestShapeSolve.h"
#include "sim/geometry/HairCurves.h"
#include "sim/solver/Solver.h"
#include "sim/solver/SolverSettings.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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

namespace {

// A lock combed out from `root` at `degreesBelowHorizontal` in the x-y plane, 20 cm in 16 segments.
HairCurves lockAt(float degreesBelowHorizontal)
{
    constexpr int kSegments = 16;
    HairCurves curves;
    const std::size_t s = curves.addStrand(kSegments + 1);
    const auto points = curves.strandForWrite(s);
    const float a = glm::radians(degreesBelowHorizontal);
    for (int j = 0; j <= kSegments; ++j)
        points[static_cast<std::size_t>(j)]
            = 0.2f * static_cast<float>(j) / kSegments * glm::vec3(std::cos(a), -std::sin(a), 0.0f);
    return curves;
}

// The tip after `steps` steps at `substeps`, released at rest from `start` with the rest shape `rest`.
glm::vec3 settledTip(const HairCurves& rest, const HairCurves& start, SolverSettings settings, int substeps, int steps)
{
    settings.substeps = substeps;
    Solver solver(1);
    EXPECT_EQ(solver.setStrands(rest), "");
    EXPECT_EQ(solver.setSettings(settings), "");
    EXPECT_TRUE(solver.setStrandState(0, start.strand(0), start.strand(0)));
    for (int i = 0; i < steps; ++i)
        solver.step();
    std::vector<glm::vec3> positions;
    solver.copyPositions(positions);
    return positions.back();
}

} // namespace

// Issue 11: the editor solves a combed rest shape for the substeps the artist asked for, and its
// pacer may then run fewer (a slow machine) or the artist more. The static shape the solver holds
// must not depend on the substep count, so the same rest shape holds the lock where it was combed
// at 1, 2, 4 and 8 substeps (today's editor default: 2). Free of the head: contact and its static
// friction hold a lock wherever it happens to stop, which would hide what this measures.
TEST(RestShapeSolve, ACombedLockHoldsWhereverThePacerTakesTheSubstepCount)
{
    SolverSettings settings;
    settings.substeps = 2;
    // 0.6: a combed strand of default hair (the comb sets 2.4 x 0.25); 0.45, softer hair combed.
    settings.dampingPerSecond = 1.0f;
    settings.dragPerSecond = 0.8f;
    for (const float stiffness : { 0.45f, 0.6f })
        for (const float below : { 0.0f, 30.0f, 50.0f }) {
            settings.stiffness = stiffness;
            const HairCurves combed = lockAt(below);
            const RestShapeSolution solved = solveRestShapes(combed, {}, settings, nullptr);
            EXPECT_LT(solved.worstGapMetres, 0.001f) << below << " degrees: the solve did not converge";
            const HairCurves unsolved = combed; // the comb's shape taken as the rest shape sags
            const float sag = glm::distance(settledTip(unsolved, combed, settings, 2, 500), combed.positions.back());
            EXPECT_GT(sag, 0.005f) << below << " degrees: the lock does not sag unsolved: the test proves nothing";
            float nearest = 1e30f, farthest = 0.0f;
            for (const int substeps : { 1, 2, 4, 8 }) {
                const float gap
                    = glm::distance(settledTip(solved.rest, combed, settings, substeps, 500), combed.positions.back());
                std::printf("[ figures  ] lock of stiffness %.2f combed %2.0f degrees below horizontal, solved at 2 "
                            "substeps, run at %d: tip %.2f mm from the comb (unsolved: %.1f mm)\n",
                    stiffness, below, substeps, gap * 1e3, sag * 1e3);
                // Before the bend's reaction made up for damping and drag: 1.3 to 2.1 mm at stiffness
                // 0.6, 9.9 to 17.9 mm at 0.45.
                EXPECT_LT(gap, 0.001f) << below << " degrees, " << substeps << " substeps: the lock left the comb";
                nearest = std::min(nearest, gap);
                farthest = std::max(farthest, gap);
            }
            EXPECT_LT(farthest - nearest, 0.0005f)
                << below << " degrees: the lock rests elsewhere at another substep count";
        }
}
