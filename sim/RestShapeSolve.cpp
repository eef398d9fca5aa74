#include "sim/RestShapeSolve.h"

#include "sim/Solver.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

namespace {

// Steps to let strands settle: with the damping below, motion falls by e^-20 in this many steps at
// 60 Hz (hair resting on the head creeps on, so half that is not enough).
constexpr int kSettleSteps = 150;
constexpr float kSettleDampingPerSecond = 8.0f;
// Each iteration turns the rest by this share of the miss: a full turn overshoots where the
// response is stronger than one to one (soft segments bent away from the vertical sag more).
constexpr float kRelaxation = 0.7f;

// v turned about the axis a x b by `share` of the angle between unit a and unit b (Rodrigues).
glm::vec3 turnedLike(const glm::vec3& a, const glm::vec3& b, const glm::vec3& v, float share)
{
    const glm::vec3 axis = glm::cross(a, b);
    const float sine = glm::length(axis);
    if (sine < 1e-7f)
        return v;  // aligned, or opposite (no shortest rotation: left to the next iteration)
    const glm::vec3 k = axis / sine;
    const float angle = share * std::atan2(sine, glm::dot(a, b));
    const float c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (1.0f - c));
}

// The rest shape whose static equilibrium in the solver (Solver.cpp's substep, no wind, no
// contact) is exactly `target`. At rest a particle does not move between substeps, so for each
// segment j with unit direction d and length h:
//   predicted - x = P = g dt² + m (keep - drag dt),  m = -s c_{j+1}  (the DFTL correction of the
//                    child moved this particle's previous position: Müller et al. 2012, eq. 9)
//   bent - x = (1 - α) P + α (T - x)   must point along d, so the length projection puts it back
// where T = parent + h t is the bending target. Solving |T - parent| = h for t gives the target
// direction; the correction c_j = x - bent follows, and feeds the parent's P (tips first). The
// rest direction r_j is t turned back by the parent's rotation from rest to now (the solver turns
// r_j by the shortest rotation from r_{j-1} to d_{j-1}; r_1 = t_1).
void exactRest(std::span<const glm::vec3> target, float stiffness, const SolverSettings& settings,
               std::span<glm::vec3> rest)
{
    const std::size_t n = target.size();
    const float dt = settings.timeStepSeconds / static_cast<float>(std::max(settings.substeps, 1));
    const float keep = std::exp(-settings.dampingPerSecond * dt);
    const glm::vec3 gravityStep = settings.gravity * dt * dt;
    std::vector<glm::vec3> t(n, glm::vec3(0.0f));
    glm::vec3 childCorrection(0.0f);
    for (std::size_t j = n - 1; j >= 1; --j) {
        const glm::vec3 segment = target[j] - target[j - 1];
        const float h = glm::length(segment);
        const glm::vec3 d = segment / h;
        const float alpha = Solver::bendAlpha(stiffness, dt, h);
        const glm::vec3 move = j + 1 < n ? -settings.velocityCorrection * childCorrection : glm::vec3(0.0f);
        const glm::vec3 u = (1.0f - alpha) * (gravityStep + move * (keep - settings.dragPerSecond * dt));
        if (alpha <= 0.0f) {  // no bending at all: nothing holds a shape
            t[j] = d;
            childCorrection = -u;
            continue;
        }
        const glm::vec3 w = u / alpha;
        const float along = glm::dot(d, w);
        const float across2 = glm::dot(w, w) - along * along;
        // Too soft to hold this segment against its load: the closest direction (mu at the vertex).
        const float mu = along + std::sqrt(std::max(h * h - across2, 0.0f));
        const glm::vec3 direction = mu * d - w;
        const float length = glm::length(direction);
        t[j] = length > 1e-12f ? direction / length : d;
        const float lambda = (mu - h) * alpha;
        childCorrection = -lambda * d;
    }
    rest[0] = target[0];
    glm::vec3 restDirection = t[1];
    rest[1] = rest[0] + restDirection * glm::distance(target[1], target[0]);
    for (std::size_t j = 2; j < n; ++j) {
        const glm::vec3 parentNow = glm::normalize(target[j - 1] - target[j - 2]);
        const glm::vec3 parentRest = restDirection;
        restDirection = glm::normalize(turnedLike(parentNow, parentRest, t[j], 1.0f));
        rest[j] = rest[j - 1] + restDirection * glm::distance(target[j], target[j - 1]);
    }
}

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
    // Each strand keeps its best rest shape so far: one strand that cannot be held (pushed into the
    // head, too soft) does not stop the others converging.
    const std::size_t count = targets.strandCount();
    std::vector<float> bestGap(count, 1e30f);
    for (std::size_t i = 0; i < count; ++i)
        if (targets.pointsIn(i) >= 2)
            exactRest(targets.strand(i), settings.stiffness * (stiffnessScales.empty() ? 1.0f : stiffnessScales[i]),
                      settings, out.rest.strandForWrite(i));
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
        float worst = 0.0f;
        for (std::size_t i = 0; i < count; ++i) {
            float gap = 0.0f;
            for (std::size_t p = targets.offsets[i]; p < targets.offsets[i + 1]; ++p)
                gap = std::max(gap, glm::distance(settled[p], targets.positions[p]));
            if (gap < bestGap[i]) {
                bestGap[i] = gap;
                const std::span<const glm::vec3> r = out.rest.strand(i);
                std::copy(r.begin(), r.end(), best.strandForWrite(i).begin());
            }
            worst = std::max(worst, gap);
        }
        out.iterations = k + 1;
        if (worst < toleranceMetres)
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
                // The rotation that takes the settled direction onto the target's, applied to the rest.
                const glm::vec3 turned = turnedLike(de, dt, dr, kRelaxation);
                previousRest = r[j];
                r[j] = r[j - 1] + turned * length;
            }
        }
    }
    out.rest = std::move(best);
    out.worstGapMetres = count == 0 ? 0.0f : *std::max_element(bestGap.begin(), bestGap.end());
    return out;
}

}  // namespace wisp
