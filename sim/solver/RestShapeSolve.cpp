#include "sim/solver/RestShapeSolve.h"

#include "sim/geometry/ShortestArc.h"

#include "sim/solver/BendingModel.h"
#include "sim/solver/Solver.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace wisp {

namespace {

// Steps to let strands settle: with the damping below, motion falls by e^-20 in this many steps at
// 60 Hz (hair resting on the head creeps on, so half that is not enough).
constexpr int kSettleSteps = 150;
constexpr float kSettleDampingPerSecond = 8.0f;
// Each iteration turns the rest by this share of the miss: a full turn overshoots where the
// response is stronger than one to one (soft segments bent away from the vertical sag more).
constexpr float kRelaxation = 0.7f;

// Substeps of the fixed-point search at most, the share of the estimated turn it takes, and the
// largest turn of one iteration (a large miss is not linear in the turn).
constexpr int kFixedPointIterations = 40;
// The settle check refines again only while a refinement cuts some strand's gap below this share
// of the one before (per strand: one strand that cannot be held must not stop the others).
constexpr float kKeepRefiningBelow = 0.8f;
constexpr float kFixedPointRelaxation = 0.8f;
constexpr float kMaxTurnRadians = 0.3f;
// Share of the last substep's velocity each iteration starts with: the resting strand keeps
// trading small DFTL corrections between its particles, a strand not yet at rest must not
// accelerate from iteration to iteration.
constexpr float kVelocityKept = 0.5f;

// The rest shapes whose static equilibrium in the solver is exactly `targets`, found with the
// solver itself, so the answer is the solver's whatever its bending, length and contact do. At
// rest nothing moves between substeps: the state (x = target, previous) must come back from one
// substep unchanged. Each iteration runs one substep from the targets, then turns every rest
// direction (root first) by the angle its segment missed, divided by the share of a bend error
// that segment's constraint moves in one substep (the response of its direction to its rest
// direction), times kFixedPointRelaxation. The previous positions carry over (they hold the DFTL
// corrections a strand at rest keeps trading between its particles).
void fixedPointRest(const HairCurves& targets, std::span<const float> stiffnessScales, const SolverSettings& settings,
    Solver& solver, HairCurves& rest)
{
    const std::size_t count = targets.strandCount();
    SolverSettings one = settings;
    one.timeStepSeconds = substepSeconds(settings); // one substep of the live solver per step
    one.substeps = 1;
    one.wind = glm::vec3(0.0f);
    one.turbulence = 0.0f;
    if (!solver.setStrands(rest).empty() || !solver.setSettings(one).empty()
        || (!stiffnessScales.empty() && !solver.setStiffnessScales(stiffnessScales).empty()))
        return;

    // Per segment: the gain that turns a missed angle into a rest turn.
    std::vector<float> gain(targets.positions.size(), 0.0f);
    std::vector<float> lengths;
    for (std::size_t i = 0; i < count; ++i) {
        const std::span<const glm::vec3> t = targets.strand(i);
        const int n = static_cast<int>(t.size());
        lengths.assign(t.size(), 0.0f);
        for (int j = 1; j < n; ++j)
            lengths[j] = glm::distance(t[j], t[j - 1]);
        const float stiffness
            = std::min(1.0f, settings.stiffness * (stiffnessScales.empty() ? 1.0f : stiffnessScales[i]));
        const float rigidity = bending::rigidity(stiffness);
        for (int j = 1; j < n; ++j) {
            // The share of a miss one substep's correction moves the child.
            const float response = bending::constraint(rigidity, one.timeStepSeconds, lengths.data(), n, j).child;
            gain[targets.offsets[i] + j] = response > 1e-4f ? kFixedPointRelaxation / response : 0.0f;
        }
    }

    // The unknowns are the bend targets' directions τ_j in the frame of the combed strand (where
    // the solver turns each rest direction once the parent lies as combed): a miss of segment j
    // turns its own τ_j and nothing else. The rest directions follow from the root: r_1 = τ_1,
    // r_j = τ_j turned back by the shortest rotation from the parent's combed direction to r_{j-1}.
    std::vector<glm::vec3> previous = targets.positions, positions, tau(targets.positions.size(), glm::vec3(0.0f));
    for (std::size_t p = 0; p < targets.positions.size(); ++p)
        tau[p] = p > 0 ? targets.positions[p] - targets.positions[p - 1] : glm::vec3(0.0f);
    for (std::size_t i = 0; i < count; ++i)
        for (std::size_t p = targets.offsets[i] + 1; p < targets.offsets[i + 1]; ++p)
            tau[p] = glm::normalize(tau[p]);
    for (int k = 0; k < kFixedPointIterations; ++k) {
        for (std::size_t i = 0; i < count; ++i) {
            const std::size_t first = targets.offsets[i], points = targets.pointsIn(i);
            solver.setStrandState(i, targets.strand(i), std::span<const glm::vec3>(previous.data() + first, points));
        }
        solver.step();
        solver.copyState(positions, previous);
        float worst = 0.0f;
        for (std::size_t i = 0; i < count; ++i) {
            const std::span<const glm::vec3> t = targets.strand(i);
            const std::size_t first = targets.offsets[i];
            const std::span<glm::vec3> r = rest.strandForWrite(i);
            glm::vec3 restDirection(0.0f), combedParent(0.0f);
            for (std::size_t j = 1; j < t.size(); ++j) {
                const std::size_t p = first + j;
                worst = std::max(worst, glm::distance(positions[p], t[j]));
                previous[p] = t[j] - kVelocityKept * (positions[p] - previous[p]); // from the target
                const float length = glm::distance(t[j], t[j - 1]);
                const glm::vec3 want = (t[j] - t[j - 1]) / length;
                const glm::vec3 got = glm::normalize(positions[p] - positions[p - 1]);
                tau[p] = glm::normalize(turnShortestArc(got, want, tau[p], gain[p], kMaxTurnRadians));
                restDirection
                    = j == 1 ? tau[p] : glm::normalize(turnShortestArc(combedParent, restDirection, tau[p], 1.0f));
                combedParent = want;
                r[j] = r[j - 1] + restDirection * length;
            }
            solver.setStrandRestDirections(i, r);
        }
        if (worst < 1e-6f)
            break;
    }
}

} // namespace

RestShapeSolution solveRestShapes(const HairCurves& targets, std::span<const float> stiffnessScales,
    const SolverSettings& settings, std::shared_ptr<const SignedDistanceField> collider, int maxIterations,
    float toleranceMetres)
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
    // The combed strands alone, without the hair around them: the volume grid's push is the other
    // hair's answer to this shape, so it is left to the live simulation, where it lays the lock over
    // the hair beneath it instead of through it; there a combed strand keeps three times the density
    // before it is pushed (HairSimulation::kCombedVolumeFactor), so the push vanishes at the combed
    // shape (README, "Hair volume").
    settle.volume = 0.0f;
    Solver solver(1);
    solver.setCollider(collider);
    std::vector<glm::vec3> settled;
    // Each strand keeps its best rest shape so far: one strand that cannot be held (pushed into the
    // head, too soft) does not stop the others converging.
    const std::size_t count = targets.strandCount();
    std::vector<float> bestGap(count, 1e30f);
    // One solver (its collision field is built once per solve: for the whole head).
    fixedPointRest(targets, stiffnessScales, settings, solver, out.rest);
    HairCurves best = out.rest;
    std::vector<float> previousGap(count, 1e30f);
    for (int k = 0; k < maxIterations; ++k) {
        if (!solver.setStrands(out.rest).empty() || !solver.setSettings(settle).empty()
            || (!stiffnessScales.empty() && !solver.setStiffnessScales(stiffnessScales).empty()))
            break;
        // Start at the target, at rest: once R is right, nothing moves.
        for (std::size_t i = 0; i < targets.strandCount(); ++i)
            solver.setStrandState(i, targets.strand(i), targets.strand(i));
        for (int s = 0; s < kSettleSteps; ++s)
            solver.step();
        solver.copyPositions(settled);
        float worst = 0.0f;
        bool improving = false;
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
            improving = improving || (gap >= toleranceMetres && gap < kKeepRefiningBelow * previousGap[i]);
            previousGap[i] = gap;
        }
        out.iterations = k + 1;
        if (worst < toleranceMetres)
            break;
        // Refining helps only while it helps some strand: a strand that cannot be held (too soft,
        // pushed by the head) keeps its best, while the others go on converging. (Stopping on the
        // worst gap alone let one such strand, caught by a comb, leave every other combed strand
        // half solved, and the whole lock sagged back.)
        if (!improving)
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
                const glm::vec3 turned = turnShortestArc(de, dt, dr, kRelaxation);
                previousRest = r[j];
                r[j] = r[j - 1] + turned * length;
            }
        }
    }
    out.rest = std::move(best);
    out.worstGapMetres = count == 0 ? 0.0f : *std::max_element(bestGap.begin(), bestGap.end());
    return out;
}

} // namespace wisp
