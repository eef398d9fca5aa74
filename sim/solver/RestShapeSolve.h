#pragma once
// Grooming against live physics: the artist combs hair into a shape while it simulates, and it
// should stay there rather than sag away once released. So the combed shape is not taken as the
// rest shape; we solve for the rest shape that, under gravity and the solver's bending, comes to
// rest at the combed shape (an inverse statics problem, as in Derouet-Jourdan et al., "Inverse
// Dynamic Hair Modeling with Frictional Contact", 2013).
//
// The solver's static equilibrium is found with the solver itself, so the answer is whatever its
// bending, length and contact do (BendingModel.h): from the combed shape, one substep at a time,
// each segment's bend target is turned by the angle the segment missed (over the share of a miss
// one substep moves), and the rest directions follow from the root. Then the result is checked by
// letting the strands settle in a real solver, and refined by fixed-point steps (turn each rest
// segment by 0.7 of the angle by which the settled segment missed the target); each strand keeps
// its best rest shape.
//
// Hair too soft to hold a shape (with the weight of a lock carried to its root, default hair
// cannot hold a lock combed sideways; stiffness 0.5 or hairspray can) cannot be held by any rest
// shape; the solve then gives its best and says how far off it is (spray it stiffer).

#include "sim/geometry/HairCurves.h"
#include "sim/solver/SolverSettings.h"

#include <memory>
#include <span>

namespace wisp {

class SignedDistanceField;

struct RestShapeSolution {
    HairCurves rest; // layout of the targets
    float worstGapMetres = 0.0f; // largest distance between a settled point and its target
    int iterations = 0;
};

// `targets`: head space, the head at identity; `stiffnessScales`: per strand (see
// Solver::setStiffnessScales), empty for 1. Uses `settings`' gravity, stiffness, substeps and time
// step; not its volume (hair-hair interaction needs the other hair, which the solve does not have; the
// live grid leaves combed hair alone at its combed density, HairSimulation::kCombedVolumeFactor). Thread: the caller's
// (single-threaded solver).
RestShapeSolution solveRestShapes(const HairCurves& targets, std::span<const float> stiffnessScales,
    const SolverSettings& settings, std::shared_ptr<const SignedDistanceField> collider, int maxIterations = 8,
    float toleranceMetres = 5e-4f);

} // namespace wisp
