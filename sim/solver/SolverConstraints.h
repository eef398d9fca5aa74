// The strand's own constraints as pure functions of the lanes, each with its formula and paper
// (after PositionBasedDynamics' solve_*Constraint): the bend toward the rest shape in the parent's
// frame (XPBD, BendingModel.h), its equal and opposite reaction on the parent, the optional global
// shape, and length by follow-the-leader. Contact and friction are in SolverContact.h. Called by
// the block kernel (SolverBlockKernel.cpp), whose serial root-to-tip chain they are written for;
// the rest-shape solve (RestShapeSolve.cpp) runs them through the solver and reads the bend's
// shares from BendingModel.h. Internal to sim/solver.
// Compiled once per SIMD target, as SolverLanes-inl.h.

#if defined(WISP_SOLVER_CONSTRAINTS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WISP_SOLVER_CONSTRAINTS_INL_H_
#undef WISP_SOLVER_CONSTRAINTS_INL_H_
#else
#define WISP_SOLVER_CONSTRAINTS_INL_H_
#endif

#include "sim/solver/SolverLanes-inl.h"
#include "sim/solver/SolverRows.h"

#include <glm/mat3x3.hpp>

#include <cstddef>
#include <type_traits>

HWY_BEFORE_NAMESPACE();
namespace wisp::HWY_NAMESPACE::kernel {

// The block's rows as the kernel reads them, one slice of kVecLanes lanes at a time (its vector is
// one register wide, lanes::Vec): the same layout as the rows (SolverRows.h), each field this
// slice's floats and then the rest of the row's lanes, so rows + slice x sizeof(Lane) bytes is
// the slice's row array. On AVX-512 a slice is the whole row.
#if WISP_LANES_AVX512
using ParticleSlice = ParticleRow;
using RestSlice = RestRow;
using ShapeSlice = ShapeRow;
using GlobalShapeSlice = GlobalShapeRow;
#else
template <int Bytes> struct OtherLanes {
    char bytes[Bytes];
};
#define WISP_SLICE_FIELD(name)                                                                                         \
    Lane name;                                                                                                         \
    OtherLanes<sizeof(wisp::Lane) - sizeof(Lane)> name##Others
struct ParticleSlice {
    WISP_SLICE_FIELD(x);
    WISP_SLICE_FIELD(y);
    WISP_SLICE_FIELD(z);
    WISP_SLICE_FIELD(px);
    WISP_SLICE_FIELD(py);
    WISP_SLICE_FIELD(pz);
    WISP_SLICE_FIELD(clearance);
};
struct RestSlice {
    WISP_SLICE_FIELD(length);
    WISP_SLICE_FIELD(bendChild);
    WISP_SLICE_FIELD(bendDamping);
    WISP_SLICE_FIELD(bendParentRatio);
    WISP_SLICE_FIELD(u);
    WISP_SLICE_FIELD(v);
};
struct ShapeSlice {
    WISP_SLICE_FIELD(x);
    WISP_SLICE_FIELD(y);
    WISP_SLICE_FIELD(z);
};
struct GlobalShapeSlice {
    WISP_SLICE_FIELD(x);
    WISP_SLICE_FIELD(y);
    WISP_SLICE_FIELD(z);
    WISP_SLICE_FIELD(share);
};
#undef WISP_SLICE_FIELD
static_assert(sizeof(ParticleSlice) == sizeof(ParticleRow)
    && offsetof(ParticleSlice, clearance) == offsetof(ParticleRow, clearance)
    && offsetof(ParticleSlice, pz) == offsetof(ParticleRow, pz));
static_assert(sizeof(RestSlice) == sizeof(RestRow) && offsetof(RestSlice, v) == offsetof(RestRow, v)
    && offsetof(RestSlice, bendParentRatio) == offsetof(RestRow, bendParentRatio));
static_assert(sizeof(ShapeSlice) == sizeof(ShapeRow) && offsetof(ShapeSlice, z) == offsetof(ShapeRow, z));
static_assert(sizeof(GlobalShapeSlice) == sizeof(GlobalShapeRow)
    && offsetof(GlobalShapeSlice, share) == offsetof(GlobalShapeRow, share));
#endif
// Slice `slice` of a row array, and of one of the block's per-lane fields. (Vector types alias
// their element type: the floats are read as they were written.)
template <class Slice, class Row> inline Slice* sliceOf(Row* rows, int slice)
{
    using Byte = std::conditional_t<std::is_const_v<Row>, const char, char>;
    return reinterpret_cast<Slice*>(reinterpret_cast<Byte*>(rows) + static_cast<std::ptrdiff_t>(slice) * sizeof(Lane));
}
inline const Lane& sliceOf(const wisp::Lane& lanes, int slice)
{
    return *reinterpret_cast<const Lane*>(
        reinterpret_cast<const char*>(&lanes) + static_cast<std::ptrdiff_t>(slice) * sizeof(Lane));
}

// (Internal linkage, as the rest of the kernel's lane code: see SolverContact.h.)
namespace {

// The bend of particle j toward its target t_j = parent + L τ (τ: the rest direction laid on the
// parent's frame now), as a spring with a damper on the motion relative to the parent, taken
// implicitly on the child (XPBD, Macklin, Müller & Chentanez 2016, eq. 18; BendingModel.h):
//   Δx_j = (parent + τ L - predicted) child - ((predicted - x) - (parent - parentStart)) damping.
// Returns bent - parent. Written so that only τ and `parent` wait on the strand's serial chain:
//   bent - parent = [predicted (1 - child) - (predicted - x) damping - parentStart damping]
//                   + parent (damping + child - 1) + τ (L child).
[[gnu::always_inline]] inline V3 bendTowardTarget(const V3& predicted, const V3& x, const V3& parentStart,
    const V3& parent, const V3& tau, Lane length, Lane child, Lane damping)
{
    const V3 besideChain = predicted * (1.0f - child) - (predicted - x) * damping - parentStart * damping;
    return besideChain + parent * (damping + child - 1.0f) + tau * (length * child);
}

// The parent's equal and opposite momentum for a bend that moved the child from `predicted` to
// parent + reach, as a velocity (DFTL's way): Δx_j m_j / m_{j-1}, raised by `gain` to make up for
// the damping and drag the next substep applies to it. Returned as the move of the parent's
// previous position.
[[gnu::always_inline]] inline V3 bendReaction(
    const V3& parent, const V3& reach, const V3& predicted, Lane parentRatio, Lane gain)
{
    return (parent + reach - predicted) * (parentRatio * gain);
}

// Global shape matching (Han & Harada 2012, "Real-time hair simulation with efficient hair style
// preservation", sec. 3.2, as AMD TressFX's global shape constraints): after the bending and before
// length and contact, particle j moves g.share of the way toward its rest position as the head
// carries it now (the root as it is this substep, the head's rotation). Only the position moves, as
// TressFX does: a projection x += s (t - x) each substep leaves an oscillation about t a factor
// sqrt(1 - s) per substep, so it adds no energy. The share is set per particle by
// Solver::updateGlobalShape: full at the root, fading along the strand, the same per second at any
// substep count.
template <bool Transformed>
[[gnu::always_inline]] inline V3 pullTowardGlobalShape(
    const V3& bent, const GlobalShapeSlice& g, const V3& root, const V3& rootHead, const glm::mat3& rotation)
{
    const V3 restHead{ g.x, g.y, g.z };
    const V3 target = Transformed ? root + transform(rotation, restHead - rootHead) : restHead;
    return bent + (target - bent) * g.share;
}

struct LengthCorrection {
    V3 position; // at rest length from the parent
    V3 correction; // position less the unconstrained position, for the DFTL velocity correction
    Lane reachLength; // |reach|: the segment's direction is reach / |reach| = reach x inverseReach
    Lane inverseReach;
};

// A rest direction's coordinates in its parent's rest frame from their stereographic projection
// (RestRow u, v): s = u² + v², l = ((1 - s), 2u, 2v) / (1 + s), a unit vector. Off the strand's
// serial chain (rest data only): its division costs throughput, not latency.
[[gnu::always_inline]] inline V3 restCoordinates(Lane u, Lane v)
{
    const Lane s = u * u + v * v;
    const Lane k = splat(1.0f) / (splat(1.0f) + s);
    return { (splat(1.0f) - s) * k, (u + u) * k, (v + v) * k };
}

// The follicle's normal: anyPerpendicular (sim/geometry/ShortestArc.h) of the root segment's rest
// direction `d`, lane by lane, with the same arithmetic (so the same bits as the scalar one).
[[gnu::always_inline]] inline V3 anyPerpendicularOf(const V3& d)
{
    const Mask upright = labs(d.y) < splat(0.9f);
    const V3 helper{ select(upright, splat(0.0f), splat(1.0f)), select(upright, splat(1.0f), splat(0.0f)),
        splat(0.0f) };
    const V3 e = cross(d, helper);
    return e * (splat(1.0f) / lsqrt(dot(e, e)));
}

// Follow the leader (Müller, Kim & Chentanez 2012, "Fast Simulation of Inextensible Hair and
// Fur", sec. 4): the particle at parent + reach is put back at rest length from its parent,
// final, along the same direction.
[[gnu::always_inline]] inline LengthCorrection followTheLeader(const V3& parent, const V3& reach, Lane length)
{
    const Lane reachLength = lsqrt(lmax(dot(reach, reach), splat(1e-24f)));
    const Lane inverseReach = splat(1.0f) / reachLength;
    // length / |reach| as one division, not length x inverseReach: the strand's chain (the next
    // particle waits for this position) runs through |reach|'s square root and this quotient, and
    // the multiply after the reciprocal was 3 more cycles on it (a limp kernel does not use
    // inverseReach at all, and its division goes). The small sphere at AVX2, one thread: 2 % faster.
    const Lane scale = length / reachLength;
    return { parent + reach * scale, reach * (scale - 1.0f), reachLength, inverseReach };
}

} // namespace

} // namespace wisp::HWY_NAMESPACE::kernel
HWY_AFTER_NAMESPACE();

#endif // per-target include guard
