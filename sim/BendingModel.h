#pragma once
// The solver's bending as numbers: one definition that the solver (Solver.cpp) and the inverse
// statics of combed hair (RestShapeSolve.cpp) both read.
//
// Model. Each segment j (particles j-1 and j) has a bending target in its parent segment's frame,
// as AMD TressFX's local shape constraints (Han & Harada 2012, "Real-time hair simulation with
// efficient hair style preservation"): the rotation R taking the parent's rest direction to its
// current direction d (shortest arc) turns the rest direction r_j, t_j = x_{j-1} + L_j τ, τ = R r_j.
// The constraint C_j = x_j - t_j is a spring of stiffness k_j, so the bending energy is
// Σ ½ k_j |C_j|², the discrete form of an elastic rod's (EI/2) ∫ κ² ds with |C| ≈ L θ = L² κ and
// k_j = B / L_j³ (Bergou et al. 2008). B is the bending rigidity over the linear density, m⁴/s².
//
// C_j depends on three particles. Moving x_{j-1} moves the target with it and, across d, turns
// the frame about x_{j-2}: with ρ = L_j / L_{j-1}, δd = P⊥(δx_{j-1} - δx_{j-2}) / L_{j-1}, and
// δτ = (d × δd) × τ = (d·τ) δd - d (τ·δd). So the gradients are G_j = I, G_{j-1} = -(I + M),
// G_{j-2} = M with M = ρ [(d·τ) P⊥ - d (P⊥τ)ᵀ]; they sum to zero, so a correction along them keeps
// the momentum (and, being the gradient of an energy, adds none). It is solved as XPBD (Macklin,
// Müller & Chentanez 2016, eq. 18, λ starting at 0 each substep):
//   (Σ_i w_i G_i G_iᵀ + α̃) λ = C,   Δx_i = -w_i G_iᵀ λ,   α̃ = 1 / (k_j dt²),
// w = 1/m with m the hair length a particle stands for (the root's w is 0: it is pinned). Written
// in the basis (d, u, v) with τ = c d + s u, the 3x3 system is a 2x2 block for (d, u) and a scalar
// for v. As dt → 0 this is Verlet integration of the spring force, so the static shape does not
// depend on the substep; a joint's angle is set by the moment it carries, which does not depend
// on the segment length, so neither does the shape on the segment count. The solver sweeps the
// constraints root to tip (Gauss-Seidel).

#include <algorithm>
#include <cmath>

namespace wisp::bending {

// Stiffness s maps to B = kRigidityScale s / (1 - s), so 1 (or more, with a region's scale) is as
// stiff as the solver can hold (α̃ = 0). At 0.25, the default, B = 2.7e-4 m⁴/s²: a 2 cm segment of
// the default 28 cm hair at 2 substeps of 1/120 s sags as it did under the bending this replaced.
constexpr float kRigidityScale = 0.0016f;  // m³/s²
constexpr float kRigidityRange = 9.21f;   // ln 10⁴: stiffness 0..1 spans four decades
constexpr float kBendDampingRatio = 6.0f;

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
        return 0.0f;  // the root: pinned
    const float inner = segmentLengths[j];
    const float outer = j + 1 < n ? segmentLengths[j + 1] : 0.0f;
    return 0.5f * (inner + outer);
}

struct Constraint {
    float child = 0.0f;        // share of C_j the child moves this substep
    float damping = 0.0f;      // share of its move relative to its parent this substep takes away
    float parentRatio = 0.0f;  // m_j / m_{j-1} (0 when j-1 is the root)
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
    const float compliance = std::isinf(rigidityB) ? 0.0f : length * length / (rigidityB * dt * dt);
    if (std::isinf(rigidityB)) {
        k.child = 1.0f;
    } else {
        // Implicit spring k and damper c = 2 ζ sqrt(k m) on the child: Δx = (w k dt² C - w c dt v dt)
        // / (1 + w k dt² + w c dt).
        const float k2 = rigidityB / (length * length);
        const float zeta = kBendDampingRatio;
        const float spring = k2 * dt * dt / mass, damper = 2.0f * zeta * std::sqrt(k2 / mass) * dt;
        k.child = spring / (1.0f + spring + damper);
        k.damping = damper / (1.0f + spring + damper);
    }
    (void)compliance;
    // The parent's equal and opposite momentum is an explicit kick; where the joint is stiff for
    // the substep (the child share near 1) a full kick overshoots, so it fades with (1 - share),
    // as DFTL's velocity correction is kept below 1 for the same reason.
    k.parentRatio = parentMass > 0.0f ? (1.0f - k.child) * mass / parentMass : 0.0f;
    return k;
}

}  // namespace wisp::bending
