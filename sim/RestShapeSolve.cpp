#include "sim/RestShapeSolve.h"

#include "sim/Solver.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace wisp {

namespace {

// Steps to let strands settle: with the damping below, motion falls by e^-10 in this many steps.
constexpr int kSettleSteps = 75;
constexpr float kSettleDampingPerSecond = 8.0f;

}  // namespace

RestShapeSolution solveRestShapes(const HairCurves& targets, std::span<const float> stiffnessScales,
                                  const SolverSettings& settings, std::shared_ptr<const SignedDistanceField> collider,
                                  int maxIterations, float toleranceMetres)
{
    RestShapeSolution out;
    out.rest = targets;
    if (targets.strandCount() == 0)
        return out;
    SolverSettings settle = settings;
    settle.wind = glm::vec3(0.0f);
    settle.turbulence = 0.0f;
    settle.dragPerSecond = 0.0f;
    settle.dampingPerSecond = std::max(settings.dampingPerSecond, kSettleDampingPerSecond);
    Solver solver(1);
    solver.setCollider(std::move(collider));
    std::vector<glm::vec3> settled;
    float bestGap = 1e30f;
    HairCurves best = out.rest;
    for (int k = 0; k < maxIterations; ++k) {
        if (!solver.setStrands(out.rest).empty() || !solver.setSettings(settle).empty())
            break;
        if (!stiffnessScales.empty())
            solver.setStiffnessScales(stiffnessScales);
        // Start at the target, at rest: once R is right, nothing moves.
        for (std::size_t i = 0; i < targets.strandCount(); ++i)
            solver.setStrandState(i, targets.strand(i), targets.strand(i));
        for (int s = 0; s < kSettleSteps; ++s)
            solver.step();
        solver.copyPositions(settled);
        float gap = 0.0f;
        for (std::size_t p = 0; p < settled.size(); ++p)
            gap = std::max(gap, glm::distance(settled[p], targets.positions[p]));
        out.iterations = k + 1;
        if (gap < bestGap) {
            bestGap = gap;
            best = out.rest;
        }
        if (gap < toleranceMetres)
            break;
        // Turn each rest segment by how far the settled segment missed the target's direction.
        for (std::size_t i = 0; i < targets.strandCount(); ++i) {
            const std::span<const glm::vec3> t = targets.strand(i);
            const std::span<glm::vec3> r = out.rest.strandForWrite(i);
            const std::size_t first = targets.offsets[i];
            glm::vec3 previousRest = r[0];
            for (std::size_t j = 1; j < t.size(); ++j) {
                const float length = glm::distance(t[j], t[j - 1]);
                const glm::vec3 dt = (t[j] - t[j - 1]) / length;
                const glm::vec3 de = glm::normalize(settled[first + j] - settled[first + j - 1]);
                const glm::vec3 dr = glm::normalize(r[j] - previousRest);
                glm::vec3 turned = dr + (dt - de);
                turned = glm::length(turned) > 1e-6f ? glm::normalize(turned) : dr;
                previousRest = r[j];
                r[j] = r[j - 1] + turned * length;
            }
        }
    }
    out.rest = std::move(best);
    out.worstGapMetres = bestGap;
    return out;
}

}  // namespace wisp
