#include "sim/solver/SolverBlockKernel.h"

#include "sim/geometry/ShortestArc.h"
#include "sim/solver/Prefetch.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

// The kernel is compiled once per SIMD target (Google Highway's dynamic dispatch: SSE4, AVX2 and
// AVX-512 on x86) and advanceBlock() runs the best the CPU has; the rest of the file once.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sim/solver/SolverBlockKernel.cpp"
#include <hwy/foreach_target.h> // (before highway.h)

#include "sim/solver/SolverConstraints.h"
#include "sim/solver/SolverContact.h"
#include "sim/solver/SolverLanes-inl.h"

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace wisp::HWY_NAMESPACE {

using namespace kernel;

namespace {

// Gusts: a few travelling sine waves in space and time per axis, sampled along each strand (advanceBlockAs);
// smooth, cheap, deterministic, and different across the head. Amplitude about 1.
// t: the time in seconds modulo 1000 (gustTime). Inlined: GCC kept it out of line, and each call
// (five a block per substep on groom-1m's 16-particle strands) passed and returned its lanes
// through memory (perf: 3 % of a groom-1m run in the function). Its arithmetic is the same either
// way (`wisp-cli simulate --out` byte-identical, with and without turbulence).
[[gnu::always_inline]] inline V3 gust(const V3& p, float t)
{
    return { 0.6f * lsin(13.0f * p.x + 7.0f * p.z + 2.3f * t)
            + 0.4f * lsin(-9.0f * p.y + 11.0f * p.z + 3.7f * t + 1.0f),
        0.6f * lsin(11.0f * p.y - 8.0f * p.x + 1.9f * t + 2.0f) + 0.4f * lsin(14.0f * p.z + 5.3f * t + 4.0f),
        0.6f * lsin(12.0f * p.z + 6.0f * p.y + 2.9f * t + 3.0f) + 0.4f * lsin(-10.0f * p.x + 4.1f * t + 5.0f) };
}

// Gusts are sampled at every this many particles along a strand and interpolated between (their
// shortest wavelength is 2π / 14 ≈ 0.45 m; a 28 cm strand of 15 segments samples every 7.5 cm).
constexpr std::uint32_t kGustStride = 4;
// The largest factor by which a bend reaction is raised to make up for the damping and drag of
// the velocity that carries it (advanceBlock): defaults at one substep need 1.03.
constexpr float kMaxKickGain = 1.1f;

} // namespace

namespace {

// A particle whose clearance bound is above this is not likely to look at the head this substep
// (a substep moves hair far less): its field nodes are not prefetched.
constexpr float kPrefetchClearanceMetres = 0.005f;

// Asks for row j of the block that follows this one in memory (blocks are laid out one after
// another and a thread runs a contiguous range of them): its first touches would otherwise stall
// the next block's serial chain on memory. A prefetch past the arrays' end is harmless.
// Of a rest row a limp block reads only the length (its first 64 bytes; the bend's shares and
// rest direction are for blocks that bend), so behind a limp block only that is asked for: the
// next block is most likely limp too, and the five other lines, which it would not read, were 38 %
// of the bytes the 1,000,000-particle sphere streamed a step (docs/performance-log.md, "The limp
// blocks' rest rows").
// Where a block is more than one slice (AVX2, SSE4), each slice's pass asks for its share of the
// lines, not the first pass for all of them at once: the 1,000,000-particle sphere at AVX2, one
// thread, 4 to 7 % faster (its eight misses a particle had come in one burst).
template <bool Bends> inline void prefetchRows(const Solver::Block& block, std::uint32_t j, int slice)
{
    constexpr int kSlices = kLanes / kVecLanes;
    int line = 0;
    const auto ahead = [&](const auto* rows, std::size_t bytes) {
        const char* at = reinterpret_cast<const char*>(rows) + (block.points + j) * sizeof(*rows);
        for (std::size_t byte = 0; byte < bytes; byte += 64, ++line)
            if (line % kSlices == slice)
                prefetchLine(at + byte);
    };
    ahead(block.state.data(), sizeof(ParticleRow));
    static_assert(offsetof(RestRow, length) == 0);
    ahead(block.rest.data(), Bends ? sizeof(RestRow) : sizeof(RestRow::length));
}

// The next block's root and follicle direction (its shape rows 0 and 1, the only ones a step
// reads): its first instructions load them, and `perf annotate` put a tenth of the kernel's time
// on that load (a cold row every block, which the hardware prefetcher does not follow: two rows
// read of every sixteen). Asked for a whole block ahead (prefetchLine, Prefetch.h: GCC dropped
// these too).
inline void prefetchNextShape(const Solver::Block& block)
{
    const char* at = reinterpret_cast<const char*>(block.shape.data() + Solver::Block::kShapeRows);
    for (std::size_t byte = 0; byte < 2 * sizeof(ShapeRow); byte += 64)
        prefetchLine(at + byte);
}

// A capsule as the particle loop reads it: its end a and axis ab splatted, 1 / |ab|² (a scalar
// division) and radius + the hair offset as lanes. The same floats as the capsule's own
// arithmetic gave, worked out once a slice instead of at every particle.
struct LaneCapsule {
    V3 a, ab;
    V3 centre; // a sphere's: a + ab 0, the point the particle loop took nearest, worked out once
    Lane inverseLength2; // 1 / |ab|², where `segment`
    Lane reach; // radius + hair offset, metres
    bool segment; // false: a sphere (a == b). (Set by laneCapsule; no default, which the particle
                  // loop stored at every look.)
};
inline LaneCapsule laneCapsule(const Capsule& capsule, float offsetMetres)
{
    LaneCapsule lanes;
    const glm::vec3 abv = capsule.b - capsule.a;
    const float ab2 = glm::dot(abv, abv);
    lanes.a = splat(capsule.a);
    lanes.ab = splat(abv);
    lanes.segment = ab2 > 0.0f;
    lanes.centre = lanes.a + lanes.ab * splat(0.0f);
    lanes.inverseLength2 = splat(lanes.segment ? 1.0f / ab2 : 0.0f);
    lanes.reach = splat(capsule.radiusMetres + offsetMetres);
    return lanes;
}

// The point of the capsule's axis nearest p: the centre of a sphere, else p's projection onto the
// segment, clamped to its ends.
[[gnu::always_inline]] inline V3 nearestOnAxis(const LaneCapsule& capsule, const V3& p)
{
    if (!capsule.segment)
        return capsule.centre;
    const Lane u = lmin(lmax(dot(p - capsule.a, capsule.ab) * capsule.inverseLength2, splat(0.0f)), splat(1.0f));
    return capsule.a + capsule.ab * u;
}

// The capsules any particle of a block can reach this step: none farther from its root than its
// strand is long (with a margin for what contact may have stretched), so a capsule beyond that
// from every root is left out for the whole step, as the head is by its clearance bound. Taken
// over the block's 16 lanes, whatever the slice: a lane then checks the same capsules on every
// target (a capsule one lane reaches is checked for all, and can touch only those it reaches).
struct CapsulesInReach {
    std::array<const Capsule*, 16> at{};
    std::size_t count = 0;
    bool filtered = false; // false: too many capsules to list, every one is checked
};
// Worked out a slice at a time on the kernel's register-wide lanes: on the block's 16-lane values
// GCC 12 took AVX2's and SSE4's arithmetic lane by lane through the stack, and this, once a block
// a step, was 13 % of the small sphere's samples at AVX2 (perf). The same floats either way.
template <bool Transformed> CapsulesInReach capsulesInReach(const Solver::Block& block, const StepConstants& c)
{
    CapsulesInReach list;
    list.filtered = c.capsulesWorld.size() <= list.at.size();
    if (!list.filtered)
        return list;
    constexpr int kSlices = kLanes / kVecLanes;
    V3 rootEnd[kSlices];
    Lane strandLength[kSlices];
    for (int slice = 0; slice < kSlices; ++slice) {
        const ShapeSlice& root = sliceOf<const ShapeSlice>(block.shape.data(), slice)[0];
        const V3 rootHead{ root.x, root.y, root.z };
        rootEnd[slice] = Transformed ? transform(c.rotation, rootHead) + splat(c.translation) : rootHead;
        strandLength[slice] = sliceOf(block.strandLength, slice);
    }
    for (const Capsule& capsule : c.capsulesWorld) {
        const LaneCapsule laidOut = laneCapsule(capsule, c.offset);
        Mask reaches = Mask{} != 0;
        for (int slice = 0; slice < kSlices; ++slice) {
            const V3 away = rootEnd[slice] - nearestOnAxis(laidOut, rootEnd[slice]);
            const Lane reach = strandLength[slice] * 1.25f + (laidOut.reach + 0.02f);
            reaches |= dot(away, away) < reach * reach;
        }
        if (anyOf(reaches))
            list.at[list.count++] = &capsule;
    }
    return list;
}

// How far a particle moved, at most, for its clearance bound: the move's taxicab length |dx| + |dy|
// + |dz|, which is never below its length (and at most √3 times it), rounded up a little (the bound
// must never shrink by less than the true move). No square root: it was a tenth of the sphere
// workload's kernel samples (perf), where a particle's bound only lets it skip a look.
[[gnu::always_inline]] inline Lane moveLength(const V3& d)
{
    return (labs(d.x) + labs(d.y) + labs(d.z)) * 1.0001f + 1e-9f;
}

// The head's distance and normal at a world-space point, for the lanes of `use`: the field is in
// head space, so a turned head's point is taken there and its normal back into the world.
template <bool Transformed>
[[gnu::always_inline]] inline SdfSample sampleHeadAt(const StepConstants& c, const V3& at, const Mask& use)
{
    SdfSample sample = sampleField(
        *c.field, Transformed ? transform(glm::transpose(c.rotation), at - splat(c.translation)) : at, use);
    if (Transformed)
        sample.normal = transform(c.rotation, sample.normal);
    return sample;
}

// The head's contact for the lanes `inside` (depth > 0 at the first look, normal there), out of
// line and on copies of the kernel's values (see HeldParticle in SolverContact.h: by address they
// would keep the strand's chain in memory through every particle): the turns onto the tangent
// plane with their looks again, the arc and the push where turning does not converge, then
// friction. Returns the particle's position and previous position.
template <bool Transformed>
[[gnu::noinline]] HeldParticle resolveHeadContact(const StepConstants& c, Mask needsLook, Mask inside, Lane depth,
    V3 normal, const ContactFriction& mu, V3 parent, Lane length, Lane inverseLength, V3 before, V3 headMove,
    V3 position, V3 previous)
{
    auto sampleHead = [&](const V3& at) __attribute__((always_inline))
    {
        return sampleHeadAt<Transformed>(c, at, needsLook);
    };
    // A curved surface is not its tangent plane: turn onto the plane, look again from
    // there, and only then push what the segment cannot reach. Friction comes once, after
    // the last look: its normal correction is what all the looks moved the particle out
    // (their depths summed), on the tangent plane where it ends (a second look's own
    // depth, nanometres on a smooth head, would have let the slide through).
    Lane contactDepth = depth;
    V3 contactNormal = normal;
    turnOutOfContactInline(inside, depth, normal, parent, length, position, false, splat(c.offset));
    // What is left within half the offset (still clear of the skin) stays: turning it
    // far along the arc below for that little would shake stiff hair lying on the head.
    const Lane slack = select(length < splat(2.0f * c.offset), splat(c.offset), splat(0.5f * c.offset));
    // The last pass only for lanes still deep before it (below): a lane's own state
    // decides, never its neighbours', so it ends alike however many lanes run together
    // (a slice of the block on each SIMD target).
    Mask wantsLastPass = Mask{} == 0;
    for (int pass = 1; pass <= kHeadContactPasses; ++pass) {
        const SdfSample next = sampleHead(position);
        const Lane nextDepth = splat(c.offset) - next.distance;
        const Mask stillInside = (nextDepth > splat(kContactResidualMetres)) & needsLook;
        const Mask stuck = stillInside & (nextDepth > slack) & wantsLastPass;
        if (!anyOf(pass < kHeadContactPasses ? stillInside : stuck))
            break;
        const Mask turns = pass < kHeadContactPasses ? stillInside : stuck;
        contactDepth = contactDepth + select(turns, nextDepth, splat(0.0f));
        contactNormal = select(turns, next.normal, contactNormal);
        if (pass < kHeadContactPasses) {
            turnOutOfContactInline(
                stillInside, nextDepth, next.normal, parent, length, position, false, splat(c.offset));
            // Turning converges fast on a smooth surface: look once more only where a
            // lane was still a quarter of the offset deep before this last turn (in a
            // crevice the last turn may put it deeper on the other wall).
            if (pass + 1 == kHeadContactPasses) {
                wantsLastPass = stillInside & (nextDepth > slack * 0.5f);
                if (!anyOf(wantsLastPass))
                    break;
            }
            continue;
        }
        // Turning did not converge (a crevice by an ear, where the normal flips from
        // wall to wall): turn along the arc toward the parent's outward normal and take
        // its first clear point, keeping the length. Only lanes that no turn gets out
        // (the parent itself too deep) are pushed, and their length gives way.
        const V3 from = (position - parent) * inverseLength;
        const V3 to = sampleHead(parent).normal;
        auto onArc = [&](Lane t) {
            const V3 v = from + (to - from) * t;
            return parent + v * (length * lrsqrt(lmax(dot(v, v), splat(1e-12f))));
        };
        const Mask arcClears = stuck & (splat(c.offset) - sampleHead(onArc(splat(1.0f))).distance <= slack);
        if (anyOf(arcClears)) {
            Lane lo = splat(0.0f), hi = splat(1.0f);
            for (int b = 0; b < kArcBisections; ++b) {
                const Lane mid = (lo + hi) * 0.5f;
                const Mask clear = splat(c.offset) - sampleHead(onArc(mid)).distance <= slack;
                hi = select(clear, mid, hi);
                lo = select(clear, lo, mid);
            }
            position = select(arcClears, onArc(hi), position);
        }
        turnOutOfContactInline(
            stuck & ~arcClears, nextDepth, next.normal, parent, length, position, true, splat(c.offset));
    }
    applyFrictionInline(
        inside, contactDepth, contactNormal, mu, parent, before, headMove, position, previous, splat(c.offset));
    return { position, previous };
}

// Substeps [firstSubstep, endSubstep) of the step for the block's lanes [slice x kVecLanes,
// (slice + 1) x kVecLanes) (kernel::Lane: one register); the last call of a step (endSubstep ==
// c.substeps) also puts back strands that went non-finite or flew away.
template <bool Transformed, bool GlobalShape, bool Bends, bool Gusty>
void advanceBlockAs(Solver::Block& block, const StepConstants& c, int firstSubstep, int endSubstep, int slice,
    const CapsulesInReach& capsules)
{
    const std::uint32_t n = block.points;
    ParticleSlice* row = sliceOf<ParticleSlice>(block.state.data(), slice);
    const RestSlice* rest = sliceOf<const RestSlice>(block.rest.data(), slice);
    const ShapeSlice* shape = sliceOf<const ShapeSlice>(block.shape.data(), slice);
    const GlobalShapeSlice* globalShape // (null while it is off: no offset on a null pointer)
        = GlobalShape ? sliceOf<const GlobalShapeSlice>(block.globalShape.data(), slice) : nullptr;
    const Lane strandLength = sliceOf(block.strandLength, slice);

    // Roots in world space at the start and the end of this step; substeps interpolate between them.
    const V3 rootHead{ shape[0].x, shape[0].y, shape[0].z };
    const V3 rootEnd = Transformed ? transform(c.rotation, rootHead) + splat(c.translation) : rootHead;
    const V3 rootStart
        = Transformed ? transform(c.previousRotation, rootHead) + splat(c.previousTranslation) : rootHead;

    // Wind (eq. 1 and 2 of the force-driven hair paper) with gusts sampled at each particle, so
    // they vary along a strand (turbulence is ours).
    const V3 ownWind = block.wind
        ? V3{ sliceOf(block.wind->x, slice), sliceOf(block.wind->y, slice), sliceOf(block.wind->z, slice) }
        : V3{};
    const V3 baseWind = splat(c.wind) + ownWind;
    const float windSpeed = glm::length(c.wind);
    const Lane gustAmplitude = splat(c.turbulence * windSpeed);
    const float gustTime = static_cast<float>(std::fmod(c.time, 1000.0));

    const V3 gravityStep = splat(c.gravity * (c.dt * c.dt));
    const Lane dt = splat(c.dt), keep = splat(c.keep);
    const Lane drag = splat(c.drag) * sliceOf(block.dragScale, slice);
    const Lane velocityCorrection = splat(c.velocityCorrection);
    // The bend's reaction on the parent (below) carries force up the strand through the parent's
    // Verlet velocity, which the next substep's predict damps (keep) and drags (1 / (1 + k dt)) as
    // if it were motion. Of the force that holds a resting lock up that takes a share which grows
    // with the substep, so a combed lock rested lower at fewer substeps than at more (issue 11: its
    // rest shape is solved at one substep count and the editor's pacer may run another). The
    // reaction is divided by that share here; capped, so strong drag or damping at a long substep
    // (where the share is no small correction) never amplifies it much.
    const Lane kickGain = lmin((splat(1.0f) + drag * dt) * splat(1.0f / c.keep), splat(kMaxKickGain));
    const ContactFriction mu{ splat(c.friction), splat(c.friction * kStaticOverKineticFriction), !(c.friction > 0.0f) };

    // The capsules in reach as lanes, once for the slice: worked out at each particle, their
    // splats, the segment's squared length and its reciprocal (a scalar division) were 3.5 % of
    // the sphere workload's instructions at AVX2 (callgrind; the same bits either way). (More
    // capsules than a block lists: each is laid out where it is checked.)
    std::array<LaneCapsule, 16> inReach;
    if (capsules.filtered)
        for (std::size_t k = 0; k < capsules.count; ++k)
            inReach[k] = laneCapsule(*capsules.at[k], c.offset);
    const std::size_t capsulesToCheck = capsules.filtered ? capsules.count : c.capsulesWorld.size();

    // Verlet (eq. 3) with drag toward the wind taken implicitly: v' = (keep v + k dt w) / (1 + k dt)
    // + g dt, which only ever moves v toward w, so any drag at any step is stable, and leaves
    // gravity whole (hair at rest feels all its weight, whatever the drag and the step). k is the
    // drag scaled by eq. 1's s = |w x t| / (|w||t|): wind across the strand pushes, along it not.
    // (Without gusts the wind is the same at every particle: its squared speed once a slice.)
    const Lane baseWindSpeed2 = dot(baseWind, baseWind);
    auto predict = [&](const V3& x, const V3& previous, const V3& parentBefore, const V3& gustHere) {
        V3 wind = baseWind;
        Lane windSpeed2 = baseWindSpeed2;
        if constexpr (Gusty) {
            wind = wind + gustHere * gustAmplitude;
            windSpeed2 = dot(wind, wind);
        }
        const Mask calm = windSpeed2 < splat(1e-12f);
        const V3 tangent = x - parentBefore;
        const Lane wt = dot(wind, tangent);
        // With D = |t|² |w|² and N = D - (w.t)² = |w x t|², s = sqrt(N / D); writing c = k dt / s
        // (the drag times dt) and R = sqrt(N D) = s D, the update is
        //   v' dt = (keep v dt D + w dt c R) / (D + c R),
        // one square root and one division a particle (the divider is what a particle's step is
        // short of on a wide target, most of all Intel's 512-bit one). In calm air s = 1: D = N = 1,
        // the same arithmetic as (keep v dt + w dt c) / (1 + c). s stays at least 1e-10.
        const Lane d = select(calm, splat(1.0f), lmax(dot(tangent, tangent), splat(1e-20f)) * windSpeed2);
        const Lane n = select(calm, splat(1.0f), lmax(d - wt * wt, d * 1e-20f));
        const Lane cr = drag * dt * lsqrt(n * d);
        const V3 move = (x - previous) * (keep * d) + wind * (cr * dt);
        return x + move * lrcp(d + cr) + gravityStep;
    };

    // Length, then contact, for particle i whose bent position is `bent` and whose parent is final
    // at `parent`: follow the leader (Müller et al. 2012) puts it at rest length from its parent,
    // then the head field and the capsules push it out (keeping that length where they can), and
    // the DFTL velocity correction (eq. 9: v_{i-1} -= s d_i / dt, in Verlet form the parent's
    // previous position moves by s d_i) damps what the length projection added. `reach` is the
    // bent position less the parent's, `before` the particle's position at the start of the
    // substep, `kick` the bend's reaction on the parent (added to its previous position with the
    // DFTL correction, one write). Returns its final position and the unit direction from the parent
    // to it: follow the leader's where contact left the particle where that put it, else worked out
    // again (so 1 / length, a division, only where contact looked).
    struct Finished {
        V3 position;
        V3 along; // the segment (parent to position) or a vector along it, so its direction is
        Lane alongLength; // along / alongLength, where alongLength = |along|
        Lane inverseAlong; // and inverseAlong = 1 / alongLength
        bool looked; // whether contact may have moved it (else it is at rest length from its parent)
    };
    auto finish = [&](std::uint32_t i, const V3& before, const V3& reach, const V3& parent, const V3& kick) {
        ParticleSlice& p = row[i];
        V3 previous = before;
        const Lane length = rest[i].length;
        const LengthCorrection ftl = followTheLeader(parent, reach, length);
        V3 position = ftl.position;
        const V3 correction = ftl.correction;
        bool looked = false; // whether contact may have moved it (else `checked` is final)
        // The head's (and the body's) own motion here over this substep, which friction takes the
        // slide relative to: none while the head stands still. Worked out where contact needs it
        // (a value made at every particle and passed by address cost a still head about 15
        // instructions a slice of a particle at AVX2, callgrind).
        auto headMoveHere
            = [&] { return Transformed ? transform(c.headMoveLinear, ftl.position) + splat(c.headMoveOffset) : V3{}; };

        // The field lookup (a node per lane, and a branch on its answer the strand's chain waits
        // for) is skipped while the clearance bound says no lane can touch: the bound shrinks by
        // each move's length, rounded up (moveLength). Every particle looking every substep took
        // groom-1m from 7.95 to 10.4 times the floor (docs/performance-log.md, "What groom-1m's step
        // is made of").
        const V3 checked = position;
        Lane clearance = p.clearance - moveLength(position - before);
        // Only the lanes whose bound ran out meet the head and the capsules: a lane's own bound
        // decides, never its neighbours' (whose lookup would otherwise have given it contact too,
        // where the field's first-order extension reads a hair's breadth inside), so a lane ends
        // alike however many lanes run together (a slice of the block on each SIMD target).
        const Mask needsLook = Transformed ? Mask{} == 0 : clearance < splat(0.0f);
        // 1 / length, once contact needs it; not set before (set to zero, it was stored to the stack
        // at every particle: 1 % of the limp kernel's instructions at AVX2).
        Lane inverseLength;
        bool haveInverseLength = false;
        auto needInverseLength = [&] {
            if (!haveInverseLength)
                inverseLength = splat(1.0f) / length;
            haveInverseLength = true;
        };
        if (c.field && anyOf(needsLook)) {
            const SdfSample sample = sampleHeadAt<Transformed>(c, position, needsLook);
            const Lane depth = splat(c.offset) - sample.distance;
            const Mask inside = (depth > splat(0.0f)) & needsLook;
            if (anyOf(inside)) {
                needInverseLength();
                const HeldParticle held = resolveHeadContact<Transformed>(c, needsLook, inside, depth, sample.normal,
                    mu, parent, length, inverseLength, before, headMoveHere(), position, previous);
                position = held.position;
                previous = held.previous;
            }
            // A moving head moves the field under the particles: no bound survives that.
            clearance = Transformed ? splat(-1e30f) : select(needsLook, lmax(-depth, splat(0.0f)), clearance);
            looked = true;
        }
        // The capsules (the neck and shoulders, the bench's sphere), like the head only for the lanes
        // whose bound ran out: the bound covers them too, the least of the lane's clearances to
        // the head and to each capsule. (They were checked at every particle: one thread, the
        // sphere workload's step 0.349 -> 0.326 ms with the bound.)
        if (capsulesToCheck > 0 && anyOf(needsLook)) {
            // Where the head's contact moved a lane, its capsule distances are measured from there:
            // less that move, they bound the lane's clearance at `checked`, as the head's does.
            const Lane headShift = looked ? moveLength(position - checked) : splat(0.0f);
            Lane capsuleClearance = splat(1e30f);
            for (std::size_t k = 0; k < capsulesToCheck; ++k) {
                LaneCapsule laidOut;
                const LaneCapsule& capsule
                    = capsules.filtered ? inReach[k] : (laidOut = laneCapsule(c.capsulesWorld[k], c.offset));
                const V3 away = position - nearestOnAxis(capsule, position);
                const Lane dist = lsqrt(dot(away, away));
                const Lane depth = capsule.reach - dist;
                capsuleClearance = lmin(capsuleClearance, -depth);
                const Mask inside = (depth > splat(0.0f)) & (dist > splat(1e-9f)) & needsLook;
                if (anyOf(inside)) {
                    needInverseLength();
                    resolveCapsuleContact<!Bends>(inside, depth, away, dist, mu, parent, length, before, headMoveHere(),
                        position, previous, splat(c.offset));
                }
            }
            const Lane fromCapsules = lmax(capsuleClearance - headShift, splat(0.0f));
            const Lane fromHead = c.field ? clearance : splat(1e30f); // (refreshed above where it looked)
            clearance = Transformed ? splat(-1e30f) : select(needsLook, lmin(fromHead, fromCapsules), clearance);
            looked = true;
        }
        if (i > 1) {
            ParticleSlice& q = row[i - 1];
            if constexpr (Bends) {
                q.px += kick.x + velocityCorrection * correction.x;
                q.py += kick.y + velocityCorrection * correction.y;
                q.pz += kick.z + velocityCorrection * correction.z;
            } else {
                q.px += velocityCorrection * correction.x;
                q.py += velocityCorrection * correction.y;
                q.pz += velocityCorrection * correction.z;
            }
        }
        // (Where nothing looked, position is `checked` and the bound stands as it is.)
        p.clearance = looked ? clearance - moveLength(position - checked) : clearance;
        p.x = position.x;
        p.y = position.y;
        p.z = position.z;
        p.px = previous.x;
        p.py = previous.y;
        p.pz = previous.z;
        Finished done{ position, reach, ftl.reachLength, ftl.inverseReach, looked };
        if (haveInverseLength) {
            const Mask moved
                = (position.x != ftl.position.x) | (position.y != ftl.position.y) | (position.z != ftl.position.z);
            done.along = select(moved, position - parent, reach);
            done.alongLength = select(moved, length, ftl.reachLength);
            done.inverseAlong = select(moved, inverseLength, ftl.inverseReach);
        }
        return done;
    };

    // Whether a strand went non-finite or flew away (checked after the step's last substep, below):
    // in the last substep's pass, as soon as their positions are final (a second pass over the rows
    // cost the small sphere about a tenth of its step), the particles contact looked at and the tip.
    // A lane stays `within` while those are less than 1.5 strand lengths and 5 cm from the root
    // (false for NaN). The others need no look: the length constraint put each at its rest length
    // from its parent, and a non-finite position reaches the tip (every particle below it is placed
    // from it). (Every particle was checked: 3 % of the small sphere's step at AVX2, one thread.)
    // Only positions: a previous position gone non-finite with its position still sound makes the
    // next step's position so (Verlet moves it by their difference), and this check takes it a step
    // later; the volume grid reads no such move in the meantime (groupSlice's `tame`). (An absurd
    // but finite one moves the particle far, and its length constraint puts it back at its length
    // from its parent, as it did when this also took |x - previous|² < 1e12 at every particle: 3 %
    // more of the small sphere's step.)
    const Lane reachLimit = strandLength * 1.5f + 0.05f;
    const Lane reachLimit2 = reachLimit * reachLimit;
    Mask within = Mask{} == 0;
    bool accounted = false; // whether the last substep ran here and looked at every row
    auto account = [&](const V3& x) {
        const V3 d = x - rootEnd;
        within &= dot(d, d) < reachLimit2;
    };
    auto rowAt = [&](std::uint32_t j) { return V3{ row[j].x, row[j].y, row[j].z }; };

    for (int s = firstSubstep; s < endSubstep; ++s) {
        const bool lastSubstep = s + 1 == c.substeps;
        const Lane t = splat(static_cast<float>(s + 1) / static_cast<float>(c.substeps));
        const V3 root = rootStart + (rootEnd - rootStart) * t;
        const V3 parentBefore{ row[0].x, row[0].y, row[0].z };
        row[0].px = row[0].x;
        row[0].py = row[0].y;
        row[0].pz = row[0].z;
        row[0].x = root.x;
        row[0].y = root.y;
        row[0].z = root.z;

        // One pass, root to tip, as follow-the-leader: each particle is predicted, bent toward
        // its target in its parent's frame, then gets its length and contact; the parent, already
        // placed, takes the bend's equal and opposite momentum as a velocity (BendingModel.h).
        // The frames are carried down the strand as it is now by parallel transport (the
        // shortest rotation from each segment's direction to the next, a Bishop frame), starting
        // from the follicle's frame, which turns with the head. The rest shape is stored in the
        // same frames of the rest strand, so turning a piece of strand rigidly turns its targets
        // with it: only bending costs.
        //
        // The strand is a serial chain (each particle waits for its parent's final position), so
        // the work is arranged to keep that chain short: everything that does not depend on the
        // parent's final position (the prediction, the bend's other terms, the next target's part
        // across the parent's direction) is computed beside it.
        V3 parent = root; // final position of particle j-1
        V3 parentStart = parentBefore; // particle j-1 at the start of the substep
        V3 gustFrom{}, gustTo{}; // gusts at the samples either side of particle j
        Lane gustSpan = splat(1.0f);
        V3 frameD{}, frameE{}, frameB{}, turned{}; // (a limp block has no frames)
        if constexpr (Bends) {
            frameD = V3{ shape[1].x, shape[1].y, shape[1].z }; // the follicle's frame: the root segment's
            frameE = anyPerpendicularOf(frameD); // rest direction and a normal to it (storeRestFrames)
            if (Transformed) {
                frameD = transform(c.rotation, frameD);
                frameE = transform(c.rotation, frameE);
            }
            frameB = cross(frameD, frameE);
            // The target direction of segment j: its rest direction's coordinates in the parent's
            // rest frame, laid on the parent's frame now.
            const V3 first = restCoordinates(rest[1].u, rest[1].v);
            turned = frameD * first.x + frameE * first.y + frameB * first.z;
        }
        // Particle j's prediction, from where it and its parent were at the start of the substep,
        // with the gusts there (sampled at every kGustStride-th particle and interpolated between:
        // they are smooth over tens of centimetres). Called for j = 1, 2, ... in turn.
        // In line, by GCC's own attribute: it left the gusty kernels' copy out of line (a C++
        // [[gnu::always_inline]] on a lambda is not applied to its call operator), so its
        // arguments, the gust samples and the particle it returns went through memory, and the
        // strand's values the loop passes it lived on the stack. Callgrind, groom-1m at AVX2 (one
        // thread, 70 steps): the kernel's instructions 7.01 G -> 5.60 G; the same bits.
        auto predictAt = [&](std::uint32_t j, const V3& x, const V3& parentBefore) __attribute__((always_inline))
        {
            V3 gustHere{};
            if constexpr (Gusty) {
                const std::uint32_t k = (j - 1) % kGustStride;
                if (k == 0) {
                    const std::uint32_t ahead = std::min(j + kGustStride, n - 1);
                    gustFrom = j == 1 ? gust(x, gustTime) : gustTo;
                    gustTo = ahead == j ? gustFrom : gust(V3{ row[ahead].x, row[ahead].y, row[ahead].z }, gustTime);
                    gustSpan = splat(1.0f / static_cast<float>(std::max<std::uint32_t>(ahead - j, 1)));
                }
                gustHere = gustFrom + (gustTo - gustFrom) * (splat(static_cast<float>(k)) * gustSpan);
            }
            return predict(x, V3{ row[j].px, row[j].py, row[j].pz }, parentBefore, gustHere);
        };
        // A limp block's prediction runs two particles ahead of the chain below AVX-512: the
        // prediction (its drag's square root and division) takes longer than the length constraint
        // it feeds, and one particle ahead the chain waited for it (the small sphere, one thread:
        // 7 % faster at AVX2, 6 % at SSE4; the same bits). Not at AVX-512 (1 % slower: its two
        // divisions a particle are two-pumped there) nor in a bending block (2-3 % slower: it has
        // more live values to carry the second one beside).
        constexpr bool kTwoAhead = !Bends && kVecLanes < 16;
        V3 predicted{}, predictedNext{}; // particle j's prediction (and j + 1's, two ahead)
        if (n > 1)
            predicted = predictAt(1, V3{ row[1].x, row[1].y, row[1].z }, parentBefore);
        if (kTwoAhead && n > 2)
            predictedNext = predictAt(2, V3{ row[2].x, row[2].y, row[2].z }, V3{ row[1].x, row[1].y, row[1].z });
        for (std::uint32_t j = 1; j < n; ++j) {
            const RestSlice& r = rest[j];
            // Particle j at the start of the substep, read from its row (which finish() writes only
            // at its end), not carried from the particle before: GCC spilled the carried copy and
            // copied it from one stack slot to another at every particle (callgrind, the small
            // sphere at AVX2: 2 % fewer instructions in the limp kernel; the same bits).
            const V3 x{ row[j].x, row[j].y, row[j].z };
            // The next block's rows (the next in memory, which this thread most likely runs next),
            // where they come from memory (StepConstants::prefetchNextBlock).
            if (c.prefetchNextBlock && s == firstSubstep)
                prefetchRows<Bends>(block, j, slice);
            // The next particle's field nodes, where it was at the start of the substep, while this
            // one is worked on, if its clearance bound is near running out (its lookup is likely).
            if (c.field && j + 1 < n) {
                const ParticleSlice& q = row[j + 1];
                const Mask likely = Transformed ? Mask{} == 0 : q.clearance < splat(kPrefetchClearanceMetres);
                if (anyOf(likely)) {
                    const V3 ahead{ q.x, q.y, q.z };
                    prefetchField(*c.field,
                        Transformed ? transform(glm::transpose(c.rotation), ahead - splat(c.translation)) : ahead,
                        likely);
                }
            }
            // The bend toward the target, and its reaction on the parent (SolverConstraints.h). A
            // limp block (no lane bends) goes straight to its length: the bend with all its shares
            // 0 moves nothing (reach = predicted - parent, no kick).
            V3 reach = predicted - parent;
            V3 kick{};
            if constexpr (Bends) {
                reach
                    = bendTowardTarget(predicted, x, parentStart, parent, turned, r.length, r.bendChild, r.bendDamping);
                kick = bendReaction(parent, reach, predicted, r.bendParentRatio, kickGain);
            }
            if constexpr (GlobalShape)
                reach = pullTowardGlobalShape<Transformed>(parent + reach, globalShape[j], root, rootHead, c.rotation)
                    - parent;
            parentStart = x;
            // The next particle's prediction and its rest direction's coordinates wait for nothing
            // this particle does (its previous position is written by the particle after it): in
            // program order before this one's length and contact, the chain's slow part, so that
            // they run beside it.
            // (Two ahead: particle j + 2's, from its and j + 1's rows, which this particle does not
            // write.)
            V3 predictedLater{}, next{};
            if (kTwoAhead && j + 2 < n)
                predictedLater = predictAt(j + 2, V3{ row[j + 2].x, row[j + 2].y, row[j + 2].z },
                    V3{ row[j + 1].x, row[j + 1].y, row[j + 1].z });
            if (!kTwoAhead && j + 1 < n)
                predictedLater = predictAt(j + 1, V3{ row[j + 1].x, row[j + 1].y, row[j + 1].z }, x);
            if (Bends && j + 1 < n)
                next = restCoordinates(rest[j + 1].u, rest[j + 1].v);
            const Finished done = finish(j, x, reach, parent, kick);
            const V3 position = done.position;
            if (Bends && j + 1 < n) {
                // Transport the frame onto this segment's direction d now: the shortest rotation
                // from D to d takes a vector v across D to v - (d.v) / (1 + D.d) (D + d), which
                // keeps it unit and across d; E, B and the next target's part across D, w, are
                // such vectors. So the next target d lx + w - (d.w) / (1 + D.d) (D + d) waits only
                // for d, not for the new frame. (No renormalisation on the chain.)
                // Taken from r = `along` (d = r / |r|): (d.v) / (1 + D.d) = (r.v) / (|r| + D.r), so
                // the dot products run beside |r|'s square root and the division waits only for
                // |r|, not for d, which waits for 1 / |r|, a second division. The clamp
                // 1 + D.d >= 1e-2 is |r| + D.r >= 1e-2 |r|.
                const V3 r = done.along;
                const V3 w = frameE * next.y + frameB * next.z;
                const Lane inverse = splat(1.0f) / lmax(done.alongLength + dot(frameD, r), done.alongLength * 1e-2f);
                const V3 d = r * done.inverseAlong;
                const V3 sum = frameD + d;
                turned = r * (done.inverseAlong * next.x) + w - sum * (dot(r, w) * inverse);
                frameE = frameE - sum * (dot(r, frameE) * inverse);
                frameB = frameB - sum * (dot(r, frameB) * inverse);
                frameD = d;
            }
            if (lastSubstep && done.looked)
                account(position);
            parent = position;
            if constexpr (kTwoAhead) {
                predicted = predictedNext;
                predictedNext = predictedLater;
            } else {
                predicted = predictedLater;
            }
        }
        if (lastSubstep) {
            account(parent); // the tip
            accounted = true;
        }
    }

    if (endSubstep != c.substeps)
        return;
    // A strand that went non-finite or flew away is put back at rest. Strands interact only through
    // the volume grid, which reads a non-finite particle as outside it, so it does not spread.
    if (!accounted) // (a call that ran no substep)
        for (std::uint32_t j = 0; j < n; ++j)
            account(rowAt(j));
    const Mask bad = ~within;
    if (anyOf(bad)) {
        for (int l = 0; l < kVecLanes; ++l) {
            if (!bad[l])
                continue;
            const int lane = slice * kVecLanes + l; // the block's
            placeLaneAtRest(block, lane, c.rotation, c.translation);
            if (block.strand[lane] >= 0)
                __atomic_fetch_add(c.resetCounter, 1, __ATOMIC_RELAXED);
        }
    }
}

// The block, a slice at a time (one on AVX-512).
template <bool Transformed, bool GlobalShape>
void advanceBlockSlices(Solver::Block& block, const StepConstants& c, int firstSubstep, int endSubstep)
{
    prefetchNextShape(block);
    const CapsulesInReach capsules = capsulesInReach<Transformed>(block, c);
    // Without gusts (no turbulence or no wind) and without bending (a limp block) the particle
    // loop carries neither their samples nor their frames.
    const bool gusty = blowsGusts(c.turbulence, c.wind);
    auto run = [&]<bool Bends, bool Gusty>() {
        for (int slice = 0; slice < kLanes / kVecLanes; ++slice)
            advanceBlockAs<Transformed, GlobalShape, Bends, Gusty>(block, c, firstSubstep, endSubstep, slice, capsules);
    };
    if (block.bends)
        gusty ? run.template operator()<true, true>() : run.template operator()<true, false>();
    else
        gusty ? run.template operator()<false, true>() : run.template operator()<false, false>();
}

} // namespace

// advanceBlock() for this target.
void advanceBlockOnTarget(
    Solver::Block& block, const StepConstants& c, int firstSubstep, int endSubstep, bool globalShape)
{
    if (c.transformed)
        globalShape ? advanceBlockSlices<true, true>(block, c, firstSubstep, endSubstep)
                    : advanceBlockSlices<true, false>(block, c, firstSubstep, endSubstep);
    else
        globalShape ? advanceBlockSlices<false, true>(block, c, firstSubstep, endSubstep)
                    : advanceBlockSlices<false, false>(block, c, firstSubstep, endSubstep);
}

} // namespace wisp::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

namespace wisp {

HWY_EXPORT(advanceBlockOnTarget);

void advanceBlock(Solver::Block& block, const StepConstants& c, int firstSubstep, int endSubstep, bool globalShape)
{
    HWY_DYNAMIC_DISPATCH(advanceBlockOnTarget)(block, c, firstSubstep, endSubstep, globalShape);
}

void storeRestFrames(Solver::Block& block, int lane, std::span<const glm::vec3> directions)
{
    RestRow* rest = block.rest.data();
    glm::vec3 d = directions[1];
    block.shape[1].x[lane] = d.x;
    block.shape[1].y[lane] = d.y;
    block.shape[1].z[lane] = d.z;
    glm::vec3 e = anyPerpendicular(d);
    rest[0].u[lane] = rest[0].v[lane] = 0.0f;
    for (std::uint32_t j = 1; j < block.points; ++j) {
        const glm::vec3 r = directions[j];
        const glm::vec3 b = glm::cross(d, e);
        // Stereographic from the -d pole; a segment folded straight back onto its parent (which no
        // hair has) lands far out but finite.
        const float fromPole = std::max(1.0f + glm::dot(r, d), 1e-6f);
        rest[j].u[lane] = glm::dot(r, e) / fromPole;
        rest[j].v[lane] = glm::dot(r, b) / fromPole;
        // Transport (d, e) onto r: the shortest rotation taking d to r.
        e = rotateShortestArc(d, r, e);
        e = glm::normalize(e - r * glm::dot(e, r));
        d = r;
    }
}

RestDirections::RestDirections(const Solver::Block& block, int lane)
    : m_block(block)
    , m_lane(lane)
{
    const ShapeRow& root = block.shape[1];
    m_direction = glm::vec3(root.x[lane], root.y[lane], root.z[lane]);
    m_normal = anyPerpendicular(m_direction); // as storeRestFrames takes it
}

glm::vec3 RestDirections::next()
{
    // storeRestFrames' walk, each direction from its coordinates in the frame before it.
    const std::uint32_t j = m_next++;
    const glm::vec3 d = m_direction, e = m_normal;
    glm::vec3 r = d; // the root segment's, as stored
    if (j > 1) {
        const RestRow& q = m_block.rest[j];
        const float u = q.u[m_lane], v = q.v[m_lane], s = u * u + v * v, k = 1.0f / (1.0f + s);
        r = glm::normalize((1.0f - s) * k * d + (u + u) * k * e + (v + v) * k * glm::cross(d, e));
    }
    const glm::vec3 transported = rotateShortestArc(d, r, e);
    m_normal = glm::normalize(transported - r * glm::dot(transported, r));
    m_direction = r;
    return r;
}

void placeLaneAtRest(Solver::Block& block, int lane, const glm::mat3& rotation, const glm::vec3& translation)
{
    const RestRow* rest = block.rest.data();
    ParticleRow* row = block.state.data();
    RestDirections directions(block, lane);
    glm::vec3 p
        = rotation * glm::vec3(block.shape[0].x[lane], block.shape[0].y[lane], block.shape[0].z[lane]) + translation;
    for (std::uint32_t j = 0; j < block.points; ++j) {
        if (j > 0)
            p += rotation * directions.next() * rest[j].length[lane];
        row[j].x[lane] = row[j].px[lane] = p.x;
        row[j].y[lane] = row[j].py[lane] = p.y;
        row[j].z[lane] = row[j].pz[lane] = p.z;
        row[j].clearance[lane] = -1.0f;
    }
}

void prefetchBlock(const Solver::Block& block)
{
    const char* at = reinterpret_cast<const char*>(&block);
    for (std::size_t byte = 0; byte < sizeof(Solver::Block); byte += 64)
        prefetchLine(at + byte);
}

} // namespace wisp

#endif // HWY_ONCE
