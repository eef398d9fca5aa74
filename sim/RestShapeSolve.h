#pragma once
// Grooming against live physics: the artist combs hair into a shape while it simulates, and it
// should stay there rather than sag away once released. So the combed shape is not taken as the
// rest shape; we solve for the rest shape that, under gravity and the solver's bending, comes to
// rest at the combed shape (an inverse statics problem, as in Derouet-Jourdan et al., "Inverse
// Dynamic Hair Modeling with Frictional Contact", 2013, here by fixed-point iteration):
//
//   R_0 = T;  repeat: E_k = where strands of rest shape R_k settle under gravity (the real solver,
//   damped, no wind);  d(R_{k+1})_j = normalize(d(R_k)_j + d(T)_j - d(E_k)_j)  per segment
//   direction, lengths kept;  until max |E_k - T| is small.
//
// Hair too soft to hold a shape (a horizontal strand at stiffness 0.05) cannot be held by any rest
// shape; the iteration then stops at its best and says how far off it is (spray it stiffer).

#include "sim/HairCurves.h"
#include "sim/SolverSettings.h"

#include <memory>
#include <span>

namespace wisp {

class SignedDistanceField;

struct RestShapeSolution {
    HairCurves rest;              // layout of the targets
    float worstGapMetres = 0.0f;  // largest distance between a settled point and its target
    int iterations = 0;
};

// `targets`: head space, the head at identity; `stiffnessScales`: per strand (see
// Solver::setStiffnessScales), empty for 1. Uses `settings`' gravity, stiffness, substeps and time
// step. Thread: the caller's (single-threaded solver).
RestShapeSolution solveRestShapes(const HairCurves& targets, std::span<const float> stiffnessScales,
                                  const SolverSettings& settings, std::shared_ptr<const SignedDistanceField> collider,
                                  int maxIterations = 12, float toleranceMetres = 5e-4f);

}  // namespace wisp
