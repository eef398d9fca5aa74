#pragma once
// The solver's bending as numbers: one definition that the solver (SolverBlockKernel.cpp) and the inverse
// statics of combed hair (RestShapeSolve.cpp) both read.
//
// Model. Each segment j (particles j-1 and j) has a bending target in its parent segment's frame,
// as AMD TressFX's local shape constraints (Han & Harada 2012, "Real-time hair simulation with
// efficient hair style preservation"): t_j = x_{j-1} + L_j τ, where τ is the rest direction r_j laid
// on the parent's frame. The frames are parallel-transported down the strand (a Bishop frame:
// each the shortest rotation of the one before), from the follicle's frame, which turns with the
// head; r_j is stored in the same frames of the rest strand, so a piece of strand turned rigidly
// has its targets turned with it (the earlier per-joint shortest arc from the parent's *rest*
// direction did not, and pumped curls into a spin).
//
// The constraint C_j = t_j - x_j is a spring k_j with a damper c_j on the particle's motion
// relative to its parent, taken implicitly on the child (XPBD, Macklin, Müller & Chentanez 2016,
// eq. 18 and its damping, λ starting at 0 each substep; the parent held where follow-the-leader
// put it, as FTL moves only the child, Müller et al. 2012):
//   Δx_j = (w k dt² C - w c dt v_rel dt) / (1 + w k dt² + w c dt),   c = 2 ζ sqrt(k m),
// and the parent takes the equal and opposite momentum as a velocity, the way DFTL's velocity
// correction does: Δv_{j-1} = -(1 - a)(m_j / m_{j-1}) Δx_j / dt, a = w k h² / (1 + w k h² + w c h)
// at a fixed h = 1/60 s. The (1 - a) fades that explicit kick where the joint is stiff (a → 1),
// where a full kick overshoots; where the joint is soft (a ≪ 1, the usual case) the momentum is
// kept. Taken at a fixed h, the share of a lock's weight that reaches its root is the same at any
// substep count, so the static shape is too.
//
// Why the shape does not depend on the substep or the segment count: as dt → 0 the child's
// correction is Verlet integration of the force k C, so the static shape (k C = the load the
// joint carries) is the same at any substep. The joint's angle is θ = |C| / L, and a joint
// carries the weight of the hair below it whatever the segment length, so the curvature θ / L is
// the same at any resolution when k = K / L² (K is the artist's stiffness as a rigidity over the
// linear density, m³/s²; the continuum is a beam that bends under the shear it carries). Masses
// m_j are the hair length a particle stands for (the root's w is 0). The damper (ζ = 8 times
// critical for a joint's own spring) stops a joint's own quick shiver; the strand's swing, far
// slower than a joint's, is hardly touched.

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

namespace wisp::bending {

// Stiffness s maps to K = kRigidityScale (e^(kRigidityRange s) - 1): four decades between limp
// and stiff, and 1 (or more, with a region's scale or hairspray) a rigid chain. At 0.25, the
// default, K = 0.0144 m³/s²: a 2 cm segment of the default 28 cm hair sags as it did under the
// bending this replaced; because the weight of the hair below now reaches the root, the default
// hangs, a combed lock needs about 0.5 and a horizontal one about 0.6.
constexpr float kRigidityScale = 0.0016f; // m³/s²
constexpr float kRigidityRange = 9.21f; // ln 10⁴: stiffness 0..1 spans four decades
constexpr float kBendDampingRatio = 8.0f;
constexpr float kFadeStepSeconds = 1.0f / 60.0f; // the longest substep the editor runs by default

inline float rigidity(float stiffness)
{
    stiffness = std::clamp(stiffness, 0.0f, 1.0f);
    if (stiffness >= 1.0f)
        return INFINITY;
    return kRigidityScale * (std::exp(kRigidityRange * stiffness) - 1.0f);
}

// The hair length particle j of a strand with segment lengths L_1..L_{n-1} stands for.
inline float particleMass(const float* segmentLengths /* [j] = L_j, [0] unused */, int n, int j)
{
    if (j <= 0)
        return 0.0f; // the root: pinned
    const float inner = segmentLengths[j];
    const float outer = j + 1 < n ? segmentLengths[j + 1] : 0.0f;
    return 0.5f * (inner + outer);
}

struct Constraint {
    float child = 0.0f; // share of C_j the child moves this substep
    float damping = 0.0f; // share of its move relative to its parent this substep takes away
    float parentRatio = 0.0f; // m_j / m_{j-1} (0 when j-1 is the root)
};

// Segment j of a strand with n particles and segment lengths L_1..L_{n-1}; substep dt seconds.
inline Constraint constraint(float rigidityB, float dt, const float* segmentLengths, int n, int j)
{
    Constraint k;
    if (!(rigidityB > 0.0f) || j < 1 || j >= n)
        return k;
    const float mass = particleMass(segmentLengths, n, j);
    const float parentMass = particleMass(segmentLengths, n, j - 1);
    const float length = segmentLengths[j];
    // Implicit spring k and damper c = 2 ζ sqrt(k m) on the child: Δx = (w k dt² C - w c dt v dt)
    // / (1 + w k dt² + w c dt); its share of C at a substep of `step` seconds.
    auto childShare = [&](float step) {
        const float k2 = rigidityB / (length * length);
        const float spring = k2 * step * step / mass, damper = 2.0f * kBendDampingRatio * std::sqrt(k2 / mass) * step;
        return std::pair{ spring / (1.0f + spring + damper), damper / (1.0f + spring + damper) };
    };
    if (std::isinf(rigidityB)) {
        k.child = 1.0f;
    } else {
        std::tie(k.child, k.damping) = childShare(dt);
    }
    // The parent's equal and opposite momentum is an explicit kick; where the joint is stiff (the
    // child's share near 1) a full kick overshoots, so it fades with (1 - share), as DFTL's
    // velocity correction is kept below 1 for the same reason. The share is taken at a fixed
    // kFadeStepSeconds, not the substep: the kick's size decides how much of the hair's weight
    // reaches the root, so it must not change with the substep count (a combed lock must rest
    // where it was combed whatever substeps the editor's pacer runs); a shorter substep only has
    // more margin.
    const float fade = std::isinf(rigidityB) ? 0.0f : 1.0f - childShare(kFadeStepSeconds).first;
    k.parentRatio = parentMass > 0.0f ? fade * mass / parentMass : 0.0f;
    return k;
}

} // namespace wisp::bending
