// Contact with the head and the body and its friction, as pure functions of the lanes (after
// PositionBasedDynamics' solve_*Constraint): the head's distance and normal at a point, the
// push-out that keeps a segment's length, and Coulomb friction. Called by the block kernel
// (SolverBlockKernel.cpp) on its slice of a block: kernel::Lane is one register of the target.
// Internal to sim/solver. Compiled once per SIMD target, as SolverLanes-inl.h.

#if defined(WISP_SOLVER_CONTACT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WISP_SOLVER_CONTACT_INL_H_
#undef WISP_SOLVER_CONTACT_INL_H_
#else
#define WISP_SOLVER_CONTACT_INL_H_
#endif

#include "sim/solver/Prefetch.h"
#include "sim/solver/SolverLanes-inl.h"
#include "sim/solver/SolverRows.h"

#include <cstddef>
#include <cstdint>
#include <cstring>

HWY_BEFORE_NAMESPACE();
namespace wisp::HWY_NAMESPACE::kernel {

// (Internal linkage, as when this lived in one file: each kernel file inlines these as it sees fit.)
namespace {

struct SdfSample {
    Lane distance;
    V3 normal;
};

// The node nearest each lane's point (head space), clamped into the grid (outside it the
// first-order extension keeps growing): its coordinates and its index in field.nodes.
struct FieldNode {
    Mask ix, iy, iz, index;
};

[[gnu::always_inline]] inline FieldNode nearestNode(const Solver::CollisionField& field, const V3& p)
{
    const float inv = 1.0f / field.cellSize;
    auto nearest = [&](Lane v, float origin, int count) {
        const Lane g = (v - origin) * inv + 0.5f;
        return __builtin_convertvector(lmin(lmax(g, splat(0.0f)), splat(static_cast<float>(count) - 0.5f)), Mask);
    };
    FieldNode n;
    n.ix = nearest(p.x, field.origin.x, field.dims.x);
    n.iy = nearest(p.y, field.origin.y, field.dims.y);
    n.iz = nearest(p.z, field.origin.z, field.dims.z);
    n.index = n.ix + n.iy * field.dims.x + n.iz * (field.dims.x * field.dims.y);
    return n;
}

// The lanes' node indices as the scalar code that loads the nodes reads them: stored once and
// read back as integers. Taken lane by lane from the register instead, each took an extract
// (vmovd, vpextrd, vextracti32x4: about 20 instructions for 16 lanes, several of them two
// micro-ops), and perf annotate put a fifth of the kernel's samples on those extracts. The same
// nodes are read either way.
struct NodeIndices {
    alignas(64) std::int32_t at[kVecLanes];
    [[gnu::always_inline]] explicit NodeIndices(const Mask& index)
    {
        std::memcpy(at, &index, sizeof at);
        asm("" : "+m"(at)); // read back from memory: GCC would otherwise take the lanes out one by one again
    }
    [[gnu::always_inline]] const glm::vec4* node(const Solver::CollisionField& field, int l) const
    {
        return field.nodes + static_cast<std::ptrdiff_t>(at[l]);
    }
};

// Asks the cache for the nodes sampleField will read near `p` (head space): the field is tens of
// megabytes, and its read was a quarter of groom-1m's step, waiting on memory. A hint only: what is
// computed does not change.
// Only the lanes in `use`.
[[gnu::always_inline]] inline void prefetchField(const Solver::CollisionField& field, const V3& p, const Mask& use)
{
    const NodeIndices index(select(use, nearestNode(field, p).index, Mask{}));
    for (int l = 0; l < kVecLanes; ++l)
        prefetchLine(index.node(field, l));
}

// The field at each lane of `use`; the other lanes read the first node (cached, and meaningless
// there): a lane nobody asked about costs no cache miss.
[[gnu::always_inline]] inline SdfSample sampleField(const Solver::CollisionField& field, const V3& p, const Mask& use)
{
    const FieldNode node = nearestNode(field, p);
    const Mask ix = node.ix, iy = node.iy, iz = node.iz;
    const NodeIndices index(select(use, node.index, Mask{}));
    SdfSample s;
    Lane d;
#if WISP_LANES_AVX512
    // The 16 nodes' (distance, normal) as four 4x4 transposes: register k of (a, b, c, e) holds
    // nodes 4k, 4k+1, 4k+2, 4k+3 in its 128-bit block k, so the unpacks and shuffles leave lane
    // m of each result with node m (a few shuffles instead of moving 64 floats one by one). (The
    // zero-masked unpacks: the plain ones start from an undefined register GCC 12 warns about.)
    auto load = [&](int l) { return _mm_loadu_ps(&index.node(field, l)->x); };
    auto gather4 = [&](int first) {
        __m512 r = _mm512_castps128_ps512(load(first));
        r = _mm512_insertf32x4(r, load(first + 4), 1);
        r = _mm512_insertf32x4(r, load(first + 8), 2);
        return _mm512_insertf32x4(r, load(first + 12), 3);
    };
    const __m512 a = gather4(0), b = gather4(1), cc = gather4(2), e = gather4(3);
    const __m512 ab0 = _mm512_maskz_unpacklo_ps(0xFFFF, a, b), ab1 = _mm512_maskz_unpackhi_ps(0xFFFF, a, b);
    const __m512 ce0 = _mm512_maskz_unpacklo_ps(0xFFFF, cc, e), ce1 = _mm512_maskz_unpackhi_ps(0xFFFF, cc, e);
    d = reinterpret_cast<Lane>(_mm512_shuffle_ps(ab0, ce0, 0x44));
    s.normal.x = reinterpret_cast<Lane>(_mm512_shuffle_ps(ab0, ce0, 0xEE));
    s.normal.y = reinterpret_cast<Lane>(_mm512_shuffle_ps(ab1, ce1, 0x44));
    s.normal.z = reinterpret_cast<Lane>(_mm512_shuffle_ps(ab1, ce1, 0xEE));
#elif WISP_LANES_AVX
    // The same transposes, eight nodes to a pair of 128-bit blocks per register.
    auto load = [&](int l) { return _mm_loadu_ps(&index.node(field, l)->x); };
    for (int half = 0; half < kVecLanes; half += 8) {
        auto gather2 = [&](int first) {
            return _mm256_insertf128_ps(_mm256_castps128_ps256(load(half + first)), load(half + first + 4), 1);
        };
        const __m256 a = gather2(0), b = gather2(1), cc = gather2(2), e = gather2(3);
        const __m256 ab0 = _mm256_unpacklo_ps(a, b), ab1 = _mm256_unpackhi_ps(a, b);
        const __m256 ce0 = _mm256_unpacklo_ps(cc, e), ce1 = _mm256_unpackhi_ps(cc, e);
        const __m256 parts[4] = { _mm256_shuffle_ps(ab0, ce0, 0x44), _mm256_shuffle_ps(ab0, ce0, 0xEE),
            _mm256_shuffle_ps(ab1, ce1, 0x44), _mm256_shuffle_ps(ab1, ce1, 0xEE) };
        std::memcpy(reinterpret_cast<float*>(&d) + half, &parts[0], sizeof parts[0]);
        std::memcpy(reinterpret_cast<float*>(&s.normal.x) + half, &parts[1], sizeof parts[1]);
        std::memcpy(reinterpret_cast<float*>(&s.normal.y) + half, &parts[2], sizeof parts[2]);
        std::memcpy(reinterpret_cast<float*>(&s.normal.z) + half, &parts[3], sizeof parts[3]);
    }
#else
    for (int l = 0; l < kVecLanes; ++l) {
        const glm::vec4 node = *index.node(field, l);
        d[l] = node.x;
        s.normal.x[l] = node.y;
        s.normal.y[l] = node.z;
        s.normal.z[l] = node.w;
    }
#endif
    const V3 nodePosition{ __builtin_convertvector(ix, Lane) * field.cellSize + field.origin.x,
        __builtin_convertvector(iy, Lane) * field.cellSize + field.origin.y,
        __builtin_convertvector(iz, Lane) * field.cellSize + field.origin.z };
    s.distance = d + dot(s.normal, p - nodePosition);
    return s;
}

// Contact, as the last word of a substep: the penetrating lanes are turned about their (final)
// parent onto the collider's tangent plane, so they leave it and keep their segment's length;
// where no point at that length from the parent is outside (the parent itself is too deep), the
// particle is pushed out along the normal and the length gives way. Then Coulomb friction at the
// position level (applyFrictionInline below), once per contact: after the head's last look, or with
// each capsule. The normal part of the velocity is kept only outward.
// Static friction of hair on skin is a little above its kinetic friction (measured hair-on-hair
// and hair-on-skin coefficients differ by about this much).
constexpr float kStaticOverKineticFriction = 1.25f;
// Looks at the head per contact: turns onto the tangent plane, then looks again from there (a
// nose or an ear is not its tangent plane); one more look takes what is still stuck along the arc
// toward its parent's normal, and pushes only what no turn gets out.
constexpr int kHeadContactPasses = 3;
// What a look after the first turn leaves alone: a turn onto the field's tangent plane lands on
// it to the float rounding of the positions (nanometres), so many turned particles read as a
// hair's breadth inside and were turned and looked at again for nothing. A micrometre is far
// below anything drawn or measured and far above that rounding.
constexpr float kContactResidualMetres = 1e-6f;
// Steps of the bisection along the arc from a stuck particle toward its parent's outward normal
// (the first clear point to within 1/64 of the arc).
constexpr int kArcBisections = 6;
// How far below the contact's tangent plane friction may leave a held point (applyFrictionInline): a
// share of the hair offset, and a floor for an offset of 0. Turning a held point about its parent
// along a curved surface sinks it a few micrometres; the next look at the head takes that.
constexpr float kFrictionSinkShareOfOffset = 0.05f;
constexpr float kFrictionSinkMetres = 1e-7f;

// (The turn and friction stay out of line in the bending kernel: inlined there they give the same
// bits, now that nothing is contracted into FMA, but made groom-1m and the sphere 3-10 % slower at
// AVX2 and AVX-512 (28 Nov: the kernel's live values spilled). A limp block's kernel, with fewer
// live values, turns a capsule's contact in line: resolveCapsuleContact<true>.)
struct ContactFriction {
    Lane kinetic; // μk
    Lane statik; // μs
    bool none = false; // μ = 0 (the scene's): friction takes nothing back, only the normal response is left
};

// Contact's normal response: the particle's velocity, relative to the collider's motion there
// (headMove), keeps no part into the collider (previous follows the particle along the normal).
[[gnu::always_inline]] inline void keepNoVelocityInto(
    Mask inside, const V3& normal, const V3& oldPosition, const V3& headMove, const V3& position, V3& previous)
{
    const Lane movedNormal = dot(position - oldPosition - headMove, normal);
    previous = select(inside, oldPosition + normal * lmin(movedNormal, splat(0.0f)), previous);
}

// Coulomb friction at the position level (Macklin et al. 2014, "Unified Particle Physics for
// Real-Time Applications", §6.1, eq. 24-25): the contact's normal correction d (its depth) bounds
// the tangential displacement Δx⊥ of the particle over the substep, relative to the collider's
// own motion there (a moving head carries the hair lying on it), that friction can take back.
// Static while |Δx⊥| < μs d: all of it is removed; else kinetic: min(μk d / |Δx⊥|, 1) Δx⊥ is.
// Removing it from the position (not only from the velocity) is what holds hair on a slope its
// static friction can hold: the turn onto the tangent plane keeps the predicted slide, and a
// velocity-only friction let that slide through every substep. The held point is turned about
// its (final) parent, at the distance contact left it there, so friction never changes a
// segment's length (and with nothing to take back, μ = 0, it moves nothing), and only where that
// stays above the contact's tangent plane (the contact stays the last word; the next look at the
// head catches the curvature). The previous position follows so that the velocity is what the
// particle really moved, less any part into the collider (relative to its motion): friction
// invents no velocity.
[[gnu::always_inline]] inline void applyFrictionInline(Mask inside, Lane depth, const V3& normal,
    const ContactFriction& mu, const V3& parent, const V3& oldPosition, const V3& headMove, V3& position, V3& previous,
    Lane band)
{
    // Without friction nothing is taken back, and the held point's turn below would only move the
    // particle by its rounding (its three square roots and two divisions were a third of the
    // divider's work of a particle in contact: the sphere workload is frictionless).
    if (mu.none) {
        keepNoVelocityInto(inside, normal, oldPosition, headMove, position, previous);
        return;
    }
    const V3 move = position - oldPosition - headMove;
    const V3 sliding = move - normal * dot(move, normal); // Δx⊥
    const Lane slide2 = dot(sliding, sliding);
    const Lane invSlide = lrsqrt(lmax(slide2, splat(1e-24f)));
    const Lane slide = slide2 * invSlide;
    const Mask sticks = slide <= mu.statik * depth;
    const Lane removedShare = select(sticks, splat(1.0f), lmin(mu.kinetic * depth * invSlide, splat(1.0f)));
    // About the parent, at the distance contact left it there (a push may have stretched the
    // segment; friction neither undoes nor adds to that).
    const V3 reach = position - parent;
    const Lane reachLength = lsqrt(dot(reach, reach));
    const V3 fromParent = reach - sliding * removedShare;
    const V3 atLength = parent + fromParent * (reachLength * lrsqrt(lmax(dot(fromParent, fromParent), splat(1e-20f))));
    // Where the held point at its length would sink below the tangent plane by more than a turn
    // may leave (the segment points into the surface), the position stays and friction acts on
    // the velocity alone: pushing it out would stretch the segment. (Rotating about the parent
    // along a curved surface sinks it a few micrometres: the next look at the head takes that.)
    const Lane sinkTolerance = band * kFrictionSinkShareOfOffset + kFrictionSinkMetres;
    const Mask holds = inside & (removedShare > splat(0.0f)) & (dot(atLength - position, normal) >= -sinkTolerance);
    position = select(holds, atLength, position);
    keepNoVelocityInto(inside, normal, oldPosition, headMove, position, previous);
}

// The contact's normal n at the particle, its segment s = position - parent, their dot product
// n . s and s's part across n, tangent = s - n (n . s), with its squared length: what the turn onto
// the tangent plane (below) is worked out from. In lengths, not in units of the segment's length (as
// u0 = s / length): no division by the length, and the turn's terms come out in metres.
struct ContactTurn {
    V3 normal;
    Lane along;
    V3 tangent;
    Lane tangent2;
};

// A surface's turn (the head's field): from its normal.
[[gnu::always_inline]] inline ContactTurn surfaceTurn(const V3& normal, const V3& segment)
{
    ContactTurn t;
    t.normal = normal;
    t.along = dot(normal, segment);
    t.tangent = segment - normal * t.along;
    t.tangent2 = dot(t.tangent, t.tangent);
    return t;
}

// A capsule's turn, from `away`, the particle less its nearest point on the capsule's axis (the
// normal is away / |away|, |away| = dist): n . s as (away . s) / |away|, so that the dot product
// runs beside |away|'s square root and its reciprocal instead of waiting for n. The contact is on
// the strand's chain (the next particle waits for it). (The tangent from away too, s - away (away .
// s) / |away|², waited less still but took two more divisions a look: slower at AVX2 and AVX-512.)
[[gnu::always_inline]] inline ContactTurn capsuleTurn(const V3& away, Lane dist, const V3& segment)
{
    ContactTurn t;
    const Lane inverseDist = splat(1.0f) / lmax(dist, splat(1e-9f));
    t.normal = away * inverseDist;
    t.along = dot(away, segment) * inverseDist;
    t.tangent = segment - t.normal * t.along;
    t.tangent2 = dot(t.tangent, t.tangent);
    return t;
}

// The contact's turn (and push) alone, for the head's looks: their friction is taken once, after
// the last look, from their summed depths (advanceBlock). Inlined where the caller has registers
// to spare (resolveCapsuleContactOnCopies below and resolveHeadContact call it out of line). `turn` is
// for the particle where it is now and its segment s = position - parent.
// `unitNormal`: the normal is a unit vector to the rounding (a capsule's, away / |away|).
[[gnu::always_inline]] inline void turnOntoTangentPlane(Mask inside, Lane depth, const ContactTurn& turn,
    const V3& parent, Lane length, V3& position, bool pushWhatIsLeft, Lane band, bool unitNormal = false)
{
    const V3& normal = turn.normal;
    // Turned about the parent, at the segment's length, until n . s is what the particle needs to
    // be on the plane, depth + n . s now (as far as the sphere allows: straight out along the
    // normal when even that is not enough); whatever depth is left is pushed out, and only that
    // much length gives way.
    const Lane reach = lmin(depth + turn.along, length);
    // The tangent's share, sqrt(length² - reach²) / |tangent|, as one square root of one quotient:
    // one divider operation each, where the unit tangent and the sine took two each.
    const Lane across2 = lmax(length * length - reach * reach, splat(0.0f));
    const Lane least = length * length * 1e-12f; // (a tangent shorter is along n: no turn)
    const Lane tangentShare = select(turn.tangent2 > least, lsqrt(across2 / lmax(turn.tangent2, least)), splat(0.0f));
    // A segment shorter than twice the hair offset only has to clear the surface itself, not the
    // offset kept above it: starting on the skin it cannot reach out of the offset, and stretching
    // it to would break its length for no contact.
    const Lane slack = select(length < band * 2.0f, band, splat(0.0f)); // only for segments that short
    // The turned point is parent + n reach + tangent share, and what is left of the depth after the
    // turn is pushed out along n. The terms that do not wait for the share (its division and square
    // root end the chain) are summed beside it.
    if (unitNormal) {
        // What the turn moved it along the normal, (turned - position) . n, is reach - n . s where n
        // is a unit vector (the tangent is across it): known before the share, so the push joins
        // the terms summed beside it (worked out from the turned point, it added a dot product and
        // three more steps to the chain).
        const Lane left = pushWhatIsLeft ? lmax(depth - slack - (reach - turn.along), splat(0.0f)) : splat(0.0f);
        position = select(inside, (parent + normal * (reach + left)) + turn.tangent * tangentShare, position);
        return;
    }
    const V3 turned = (parent + normal * reach) + turn.tangent * tangentShare;
    const Lane left = pushWhatIsLeft ? lmax(depth - slack - dot(turned - position, normal), splat(0.0f)) : splat(0.0f);
    position = select(inside, turned + normal * left, position);
}
[[gnu::always_inline]] inline void turnOutOfContactInline(Mask inside, Lane depth, const V3& normal, const V3& parent,
    Lane length, V3& position, bool pushWhatIsLeft, Lane band)
{
    const ContactTurn turn = surfaceTurn(normal, position - parent);
    turnOntoTangentPlane(inside, depth, turn, parent, length, position, pushWhatIsLeft, band);
}
// A capsule's turn (and push) from `away` and |away| = dist (capsuleTurn); returns the contact's
// normal, for friction and the normal response.
[[gnu::always_inline]] inline V3 turnOutOfCapsuleInline(
    Mask inside, Lane depth, const V3& away, Lane dist, const V3& parent, Lane length, V3& position, Lane band)
{
    const ContactTurn turn = capsuleTurn(away, dist, position - parent);
    turnOntoTangentPlane(inside, depth, turn, parent, length, position, true, band, true);
    return turn.normal;
}
// Out of line, the turn and friction take the kernel's values as copies and give back what they
// change, never a kernel variable by address: a variable whose address reaches an out-of-line call
// lives in memory for the whole particle loop (GCC does not keep it in registers around the call's
// rare branch), and the strand's serial chain (the parent's position, the particle's) then went
// through the stack at every particle, contact or not (callgrind, the sphere at AVX2: 13 % of the
// limp kernel's instructions; 2 threads, ten interleaved rounds, 2.62 -> 2.22 x the floor). One call
// a contact (resolveCapsuleContact here, the head's in SolverBlockKernel.cpp), each copying its arguments.

// A particle's position and previous position, as contact and friction leave them.
struct HeldParticle {
    V3 position;
    V3 previous;
};
[[gnu::noinline]] HeldParticle applyFrictionOnCopies(Mask inside, Lane depth, V3 normal, const ContactFriction& mu,
    V3 parent, V3 oldPosition, V3 headMove, V3 position, V3 previous, Lane band)
{
    applyFrictionInline(inside, depth, normal, mu, parent, oldPosition, headMove, position, previous, band);
    return { position, previous };
}
[[gnu::noinline]] HeldParticle resolveCapsuleContactOnCopies(Mask inside, Lane depth, V3 away, Lane dist,
    const ContactFriction& mu, V3 parent, Lane length, V3 oldPosition, V3 headMove, V3 position, V3 previous, Lane band)
{
    const V3 normal = turnOutOfCapsuleInline(inside, depth, away, dist, parent, length, position, band);
    applyFrictionInline(inside, depth, normal, mu, parent, oldPosition, headMove, position, previous, band);
    return { position, previous };
}

// A capsule's contact and its friction in one (one look): `away` is the particle less its nearest
// point on the axis, |away| = dist, depth the capsule's reach less dist. `Limp`: the limp
// kernel's way, the turn and the normal response of frictionless contact in the caller's code (its
// loop has the registers), friction out of line; else all of it out of line (the bending kernel's
// values spill around it inlined). The same bits either way.
template <bool Limp>
inline void resolveCapsuleContact(Mask inside, Lane depth, const V3& away, Lane dist, const ContactFriction& mu,
    const V3& parent, Lane length, const V3& oldPosition, const V3& headMove, V3& position, V3& previous, Lane band)
{
    HeldParticle held;
    if constexpr (Limp) {
        const V3 normal = turnOutOfCapsuleInline(inside, depth, away, dist, parent, length, position, band);
        if (mu.none) {
            keepNoVelocityInto(inside, normal, oldPosition, headMove, position, previous);
            return;
        }
        held
            = applyFrictionOnCopies(inside, depth, normal, mu, parent, oldPosition, headMove, position, previous, band);
    } else {
        held = resolveCapsuleContactOnCopies(
            inside, depth, away, dist, mu, parent, length, oldPosition, headMove, position, previous, band);
    }
    position = held.position;
    previous = held.previous;
}

} // namespace

} // namespace wisp::HWY_NAMESPACE::kernel
HWY_AFTER_NAMESPACE();

#endif // per-target include guard
