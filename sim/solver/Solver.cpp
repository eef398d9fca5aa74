#include "sim/solver/Solver.h"

#include "sim/geometry/ShortestArc.h"

#include "sim/geometry/SignedDistanceField.h"
#include "sim/solver/BendingModel.h"
#include "sim/solver/HairVolumeGrid.h"
#include "sim/util/ThreadPool.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif
#include <array>
#include <cmath>
#include <map>
#include <span>

namespace wisp {

// ---------------------------------------------------------------------------------------------
// Lanes: 8 floats handled by one instruction (GCC/Clang vector extension: AVX, or two SSE halves).
constexpr int kLanes = 16;
using Lane = float __attribute__((vector_size(kLanes * sizeof(float))));
using Mask = int __attribute__((vector_size(kLanes * sizeof(int))));

namespace {

inline Lane splat(float v)
{
    return Lane{} + v;
}
inline Lane select(Mask m, Lane a, Lane b)
{
    return m ? a : b;
}

// min, max, |a| and "any lane set" as single instructions per register. GCC lowers the portable
// forms (a < b ? a : b, a reduction loop) to compare-and-blend, or, for a 16-lane vector on an
// AVX2 machine, to scalar code lane by lane. minps/maxps return their second operand when the
// first comparison fails (NaN included), exactly as a < b ? a : b does, so results are unchanged.
#if defined(__AVX512F__)
static_assert(sizeof(Lane) == sizeof(__m512));
// (The zero-masked forms: the plain ones start from an undefined register GCC 12 warns about.)
inline Lane lmin(Lane a, Lane b)
{
    return reinterpret_cast<Lane>(
        _mm512_maskz_min_ps(0xFFFF, reinterpret_cast<__m512>(a), reinterpret_cast<__m512>(b)));
}
inline Lane lmax(Lane a, Lane b)
{
    return reinterpret_cast<Lane>(
        _mm512_maskz_max_ps(0xFFFF, reinterpret_cast<__m512>(a), reinterpret_cast<__m512>(b)));
}
inline bool anyOf(Mask m)
{
    const __m512i v = reinterpret_cast<__m512i>(m);
    return _mm512_test_epi32_mask(v, v) != 0;
}
#elif defined(__AVX__)
template <typename Op> inline Lane byHalves(Lane a, Lane b, Op op)
{
    Lane r;
    for (int i = 0; i < kLanes; i += 8) {
        __m256 x, y;
        std::memcpy(&x, reinterpret_cast<const float*>(&a) + i, sizeof x);
        std::memcpy(&y, reinterpret_cast<const float*>(&b) + i, sizeof y);
        x = op(x, y);
        std::memcpy(reinterpret_cast<float*>(&r) + i, &x, sizeof x);
    }
    return r;
}
inline Lane lmin(Lane a, Lane b)
{
    return byHalves(a, b, [](__m256 x, __m256 y) { return _mm256_min_ps(x, y); });
}
inline Lane lmax(Lane a, Lane b)
{
    return byHalves(a, b, [](__m256 x, __m256 y) { return _mm256_max_ps(x, y); });
}
inline bool anyOf(Mask m)
{
    __m256 lo, hi; // comparison masks: every lane all ones or all zeros, so the sign bits say it
    std::memcpy(&lo, &m, sizeof lo);
    std::memcpy(&hi, reinterpret_cast<const int*>(&m) + 8, sizeof hi);
    return !_mm256_testz_ps(_mm256_or_ps(lo, hi), _mm256_or_ps(lo, hi));
}
#else
inline Lane lmin(Lane a, Lane b)
{
    return a < b ? a : b;
}
inline Lane lmax(Lane a, Lane b)
{
    return a > b ? a : b;
}
inline bool anyOf(Mask m)
{
    int any = 0;
    for (int i = 0; i < kLanes; ++i)
        any |= m[i];
    return any != 0;
}
#endif
inline Lane lsqrt(Lane a)
{
    Lane r;
    for (int i = 0; i < kLanes; ++i)
        r[i] = __builtin_sqrtf(a[i]);
    return r;
}
// 1/sqrt(a) for a > 0: the hardware estimate refined by one Newton step (about 23 correct bits),
// far shorter latency than sqrt then divide on the strand's serial parent-to-child chain.
inline Lane lrsqrt(Lane a)
{
#if defined(__AVX512F__)
    static_assert(sizeof(Lane) == sizeof(__m512));
    // (the zero-masked form: the plain one starts from an undefined register GCC 12 warns about)
    const Lane y = reinterpret_cast<Lane>(_mm512_maskz_rsqrt14_ps(0xFFFF, reinterpret_cast<__m512>(a)));
#elif defined(__AVX__)
    Lane y;
    for (int i = 0; i < kLanes; i += 8) {
        __m256 half;
        std::memcpy(&half, reinterpret_cast<const float*>(&a) + i, sizeof half);
        half = _mm256_rsqrt_ps(half);
        std::memcpy(reinterpret_cast<float*>(&y) + i, &half, sizeof half);
    }
#else
    const Lane y = splat(1.0f) / lsqrt(a);
    return y;
#endif
#if defined(__AVX__)
    return y * (1.5f - 0.5f * a * y * y);
#endif
}

// 1/a for a > 0: the hardware estimate refined by one Newton step (about 23 correct bits), far
// shorter latency than a divide.
inline Lane lrcp(Lane a)
{
#if defined(__AVX512F__)
    const Lane y = reinterpret_cast<Lane>(_mm512_maskz_rcp14_ps(0xFFFF, reinterpret_cast<__m512>(a)));
#elif defined(__AVX__)
    Lane y;
    for (int i = 0; i < kLanes; i += 8) {
        __m256 half;
        std::memcpy(&half, reinterpret_cast<const float*>(&a) + i, sizeof half);
        half = _mm256_rcp_ps(half);
        std::memcpy(reinterpret_cast<float*>(&y) + i, &half, sizeof half);
    }
#else
    return splat(1.0f) / a;
#endif
#if defined(__AVX__)
    return y * (2.0f - a * y);
#endif
}

struct V3 {
    Lane x, y, z;
};
inline V3 operator+(const V3& a, const V3& b)
{
    return { a.x + b.x, a.y + b.y, a.z + b.z };
}
inline V3 operator-(const V3& a, const V3& b)
{
    return { a.x - b.x, a.y - b.y, a.z - b.z };
}
inline V3 operator*(const V3& a, Lane s)
{
    return { a.x * s, a.y * s, a.z * s };
}
inline Lane dot(const V3& a, const V3& b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
// |a| by clearing the sign bit (one and; -0 becomes +0, which no comparison tells apart).
inline Lane labs(Lane a)
{
    return reinterpret_cast<Lane>(reinterpret_cast<Mask>(a) & 0x7fffffff);
}
inline Lane l1Length(const V3& a)
{
    return labs(a.x) + labs(a.y) + labs(a.z);
}
inline V3 cross(const V3& a, const V3& b)
{
    return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
inline V3 select(Mask m, const V3& a, const V3& b)
{
    return { m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z };
}
inline V3 splat(const glm::vec3& v)
{
    return { splat(v.x), splat(v.y), splat(v.z) };
}
inline V3 transform(const glm::mat3& m, const V3& v) // m * v, glm is column-major
{
    return { v.x * m[0][0] + v.y * m[1][0] + v.z * m[2][0], v.x * m[0][1] + v.y * m[1][1] + v.z * m[2][1],
        v.x * m[0][2] + v.y * m[1][2] + v.z * m[2][2] };
}

} // namespace

// Particle j of the block's 8 strands: position and previous position (Verlet keeps no velocity).
struct Solver::ParticleRow {
    Lane x, y, z;
    Lane px, py, pz;
    // A lower bound on (distance to the head - hair offset) at x: while it stays positive the head
    // cannot be touched and its lookup is skipped. Negative means unknown.
    Lane clearance;
};
// Rest shape, head space, as a step reads it: row j > 0 holds the segment from particle j-1 to j
// (row 0 the follicle's frame). The rest directions themselves (ShapeRow) are kept apart: a step
// reads only the first two rows of them, and every byte a step streams costs time on a large groom.
struct Solver::RestRow {
    Lane length; // (its reciprocal is divided out beside the chain: four fewer bytes to stream)
    // Bending (BendingModel.h): the shares of this segment's bend error t_j - x_j added to
    // particle j, taken from its parent j-1 and added to j-2, for this substep (they sum to zero
    // momentum).
    Lane bendChild; // share of the bend error moved onto particle j this substep
    Lane bendDamping; // share of its move relative to its parent taken away this substep
    Lane bendParentRatio; // m_j / m_{j-1}
    // Row j > 0: the rest direction in the parent segment's rest frame (direction, normal,
    // binormal; see advanceBlock). Row 0: the follicle frame's normal, head space.
    Lane lx, ly, lz;
};
// Row 0: the root position. Row j > 0: unit direction from particle j-1 to j. Head space.
struct Solver::ShapeRow {
    Lane x, y, z;
};

// Global shape (pullTowardGlobalShape), only while it is on: particle j's rest position (head
// space) and the share of the way to it this particle moves per substep.
struct Solver::GlobalShapeRow {
    Lane x, y, z;
    Lane share;
};

using ParticleRow = Solver::ParticleRow;
using RestRow = Solver::RestRow;
using ShapeRow = Solver::ShapeRow;
using GlobalShapeRow = Solver::GlobalShapeRow;

struct Solver::Block {
    std::uint32_t points = 0;
    std::array<std::int64_t, kLanes> strand{}; // index into the caller's curves, -1 for padding
    Lane strandLength{}; // rest arc length per lane, metres
    Lane stiffnessScale{}; // per lane: multiplies the settings' stiffness
    Lane dragScale{}; // per lane: multiplies the drag toward the wind (wet hair)
    Lane windX{}, windY{}, windZ{}; // per lane: wind of its own, m/s world (a hair dryer)
    Lane volumeWeight{}; // per lane: metres of drawn hair one particle stands for (0: padding)
    Lane volumeTargetScale{}; // per lane: multiplies the density the hair keeps (wet hair)
    // The grid's level of detail at the block's last splat (Solver::volumeSplat): every
    // volumeStride-th lane splats the weight of the lanes it stands for and is sampled.
    int volumeStride = 1;
    // Views into the solver's two row arrays: every block's rows follow the previous block's, so
    // a thread streams through memory in one sequential run that the prefetcher can follow.
    std::span<ParticleRow> state;
    std::span<RestRow> rest;
    std::span<ShapeRow> shape;
    std::span<const GlobalShapeRow> globalShape; // empty while the global shape is off
};

struct StepConstants {
    float dt = 0.0f; // substep, seconds
    float keep = 1.0f; // exp(-damping dt): share of velocity kept
    float friction = 0;
    float offset = 0;
    float velocityCorrection = 0;
    float drag = 0;
    float turbulence = 0;
    int substeps = 1;
    int substep = 0; // the volume pass's substep (Solver::volumePass)
    double time = 0;
    glm::vec3 gravity{ 0.0f };
    glm::vec3 wind{ 0.0f };
    glm::mat3 rotation{ 1.0f }; // head to world
    glm::vec3 translation{ 0.0f };
    glm::mat3 previousRotation{ 1.0f };
    glm::vec3 previousTranslation{ 0.0f };
    bool transformed = false; // head is not at the identity: SDF lookups need head space
    const Solver::CollisionField* field = nullptr;
    std::vector<Capsule> capsulesWorld;
    std::uint64_t* resetCounter = nullptr;
};

namespace {

// sin(x) for the gusts: x reduced to [-pi, pi], then an odd polynomial (Taylor to x^11, error
// below 1e-3). Vectorised so that turbulence costs a few instructions per strand, not six libm calls.
inline Lane lsin(Lane x)
{
    constexpr float kInvTwoPi = 0.15915494f, kTwoPi = 6.2831853f;
    const Lane turns = x * kInvTwoPi;
    const Lane rounded = (turns + 12582912.0f) - 12582912.0f; // round to nearest (|turns| < 2^22)
    const Lane r = x - rounded * kTwoPi;
    const Lane r2 = r * r;
    return r
        * (1.0f
            + r2
                * (-1.0f / 6
                    + r2 * (1.0f / 120 + r2 * (-1.0f / 5040 + r2 * (1.0f / 362880 + r2 * (-1.0f / 39916800))))));
}

// Gusts: a few travelling sine waves in space and time per axis, evaluated at the strand's root;
// smooth, cheap, deterministic, and different across the head. Amplitude about 1.
// t: the time in seconds modulo 1000 (gustTime).
V3 gust(const V3& p, float t)
{
    return { 0.6f * lsin(13.0f * p.x + 7.0f * p.z + 2.3f * t)
            + 0.4f * lsin(-9.0f * p.y + 11.0f * p.z + 3.7f * t + 1.0f),
        0.6f * lsin(11.0f * p.y - 8.0f * p.x + 1.9f * t + 2.0f) + 0.4f * lsin(14.0f * p.z + 5.3f * t + 4.0f),
        0.6f * lsin(12.0f * p.z + 6.0f * p.y + 2.9f * t + 3.0f) + 0.4f * lsin(-10.0f * p.x + 4.1f * t + 5.0f) };
}

} // namespace

// The head as the solver reads it: for every node of the baked signed-distance grid, the distance
// and the unit outward normal there (SignedDistanceField::samplesWithNormals, built once per head
// and shared by every solver colliding with it: a comb release's rest solve and regroom no longer
// rebuild it, which was most of their cost). A lookup takes the nearest node and
// extends it to first order, d(p) = d_n + n . (p - x_n): one 16-byte load per particle instead of
// the eight scattered loads of trilinear interpolation, which dominated the step. The error is
// about h^2 / (2 R) for a surface of curvature radius R (0.03 mm for a 2.5 mm grid on a head).
struct Solver::CollisionField {
    const glm::vec4* nodes = nullptr; // (distance, normal) per node, metres: the field's own table
    glm::ivec3 dims{ 0 };
    glm::vec3 origin{ 0.0f };
    float cellSize = 0.0f;

    explicit CollisionField(const SignedDistanceField& sdf)
        : nodes(sdf.samplesWithNormals().data())
        , dims(sdf.dims())
        , origin(sdf.origin())
        , cellSize(sdf.cellSize())
    {
    }
};

namespace {

struct SdfSample {
    Lane distance;
    V3 normal;
};

[[gnu::always_inline]] inline SdfSample sampleField(const Solver::CollisionField& field, const V3& p)
{
    const float inv = 1.0f / field.cellSize;
    // Nearest node, clamped into the grid; outside it the first-order extension keeps growing.
    auto nearest = [&](Lane v, float origin, int count) {
        const Lane g = (v - origin) * inv + 0.5f;
        return __builtin_convertvector(lmin(lmax(g, splat(0.0f)), splat(static_cast<float>(count) - 0.5f)), Mask);
    };
    const Mask ix = nearest(p.x, field.origin.x, field.dims.x);
    const Mask iy = nearest(p.y, field.origin.y, field.dims.y);
    const Mask iz = nearest(p.z, field.origin.z, field.dims.z);
    const Mask index = ix + iy * field.dims.x + iz * (field.dims.x * field.dims.y);
    SdfSample s;
    Lane d;
#if defined(__AVX512F__)
    // The 16 nodes' (distance, normal) as four 4x4 transposes: register k of (a, b, c, e) holds
    // nodes 4k, 4k+1, 4k+2, 4k+3 in its 128-bit block k, so the unpacks and shuffles leave lane
    // m of each result with node m (a few shuffles instead of moving 64 floats one by one). (The
    // zero-masked unpacks: the plain ones start from an undefined register GCC 12 warns about.)
    auto load = [&](int l) { return _mm_loadu_ps(&field.nodes[static_cast<std::size_t>(index[l])].x); };
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
#elif defined(__AVX__)
    // The same transposes, eight nodes to a pair of 128-bit blocks per register.
    auto load = [&](int l) { return _mm_loadu_ps(&field.nodes[static_cast<std::size_t>(index[l])].x); };
    for (int half = 0; half < kLanes; half += 8) {
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
    for (int l = 0; l < kLanes; ++l) {
        const glm::vec4 node = field.nodes[static_cast<std::size_t>(index[l])];
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
// particle is pushed out along the normal and the length gives way. Then Coulomb friction
// (velocity level, through the previous position): the contact's normal correction δ = depth
// bounds the tangential slip it can stop, static while the slip is under μs δ, else the slip is
// shortened by μk δ (Macklin et al. 2014, "Unified Particle Physics", eq. 24-25). Its effect per
// second is μ × normal force / mass at any substep count. The normal part of the velocity is
// kept only outward.
// Static friction of hair on skin is a little above its kinetic friction (measured hair-on-hair
// and hair-on-skin coefficients differ by about this much).
constexpr float kStaticOverKineticFriction = 1.25f;
// Looks at the head per contact: turns onto the tangent plane, then looks again from there (a
// nose or an ear is not its tangent plane); one more look takes what is still stuck along the arc
// toward its parent's normal, and pushes only what no turn gets out.
constexpr int kHeadContactPasses = 3;
// Steps of the bisection along the arc from a stuck particle toward its parent's outward normal
// (the first clear point to within 1/64 of the arc).
constexpr int kArcBisections = 6;
// Gusts are sampled at every this many particles along a strand and interpolated between (their
// shortest wavelength is 2π / 14 ≈ 0.45 m; a 28 cm strand of 15 segments samples every 7.5 cm).
constexpr std::uint32_t kGustStride = 4;
// The largest factor by which a bend reaction is raised to make up for the damping and drag of
// the velocity that carries it (advanceBlock): defaults at one substep need 1.03.
constexpr float kMaxKickGain = 1.1f;
// Global shape (pullTowardGlobalShape): its share is given per step of this length, and fades from
// full at the root to none at this fraction of the strand's rest length (TressFX's "effective
// range"; the tips stay free to move, the part near the root keeps the groom).
constexpr float kGlobalShapeStepSeconds = 1.0f / 60.0f;
constexpr float kGlobalShapeReach = 0.75f;

struct ContactFriction {
    Lane kinetic; // μk
    Lane statik; // μs
};

// Coulomb friction for the lanes in contact (`inside`) that now sit at `position` (below).
inline void applyFriction(Mask inside, Lane depth, const V3& normal, const ContactFriction& mu, const V3& oldPosition,
    const V3& position, V3& previous);

inline void resolveContact(Mask inside, Lane depth, const V3& normal, const ContactFriction& mu, const V3& parent,
    Lane length, Lane inverseLength, const V3& oldPosition, V3& position, V3& previous, bool pushWhatIsLeft, Lane band)
{
    const V3 u0 = (position - parent) * inverseLength;
    const Lane along = dot(normal, u0);
    const Lane needed = depth * inverseLength + along; // n . u the particle needs to be on the plane
    const V3 tangent = u0 - normal * along;
    const Lane tangent2 = dot(tangent, tangent);
    // Turned as far as the sphere allows (straight out along the normal when even that is not
    // enough); whatever depth is left is pushed out, and only that much length gives way.
    const Lane reach = lmin(needed, splat(1.0f));
    const V3 unitTangent
        = tangent * select(tangent2 > splat(1e-12f), lrsqrt(lmax(tangent2, splat(1e-12f))), splat(0.0f));
    const Lane sine2 = lmax(splat(1.0f) - reach * reach, splat(0.0f));
    const Lane sine = sine2 * lrsqrt(lmax(sine2, splat(1e-20f)));
    const V3 turned = parent + (normal * reach + unitTangent * sine) * length;
    // A segment shorter than twice the hair offset only has to clear the surface itself, not the
    // offset kept above it: starting on the skin it cannot reach out of the offset, and stretching
    // it to would break its length for no contact.
    const Lane slack = select(length < band * 2.0f, band, splat(0.0f)); // only for segments that short
    const Lane left = pushWhatIsLeft ? lmax(depth - slack - dot(turned - position, normal), splat(0.0f)) : splat(0.0f);
    position = select(inside, turned + normal * left, position);
    applyFriction(inside, depth, normal, mu, oldPosition, position, previous);
}

inline void applyFriction(Mask inside, Lane depth, const V3& normal, const ContactFriction& mu, const V3& oldPosition,
    const V3& position, V3& previous)
{
    const V3 move = position - oldPosition;
    const Lane normalPart = dot(move, normal);
    const V3 sliding = move - normal * normalPart;
    const Lane slide2 = dot(sliding, sliding);
    const Lane invSlide = lrsqrt(lmax(slide2, splat(1e-24f)));
    const Lane slide = slide2 * invSlide;
    const Mask sticks = slide <= mu.statik * depth;
    const Lane keptShare = select(sticks, splat(0.0f), lmax(splat(1.0f) - mu.kinetic * depth * invSlide, splat(0.0f)));
    const V3 kept = sliding * keptShare + normal * lmax(normalPart, splat(0.0f));
    previous = select(inside, position - kept, previous);
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
V3 pullTowardGlobalShape(
    const V3& bent, const GlobalShapeRow& g, const V3& root, const V3& rootHead, const glm::mat3& rotation)
{
    const V3 restHead{ g.x, g.y, g.z };
    const V3 target = Transformed ? root + transform(rotation, restHead - rootHead) : restHead;
    return bent + (target - bent) * g.share;
}

// The rest shape's parallel-transported frames (advanceBlock): the follicle's normal (any unit
// vector across the root segment, chosen the same way every time) into row 0, and each rest
// direction's coordinates in its parent segment's frame into rows j > 0.
void storeRestFrames(Solver::Block& block, int lane)
{
    RestRow* rest = block.rest.data();
    const ShapeRow* shape = block.shape.data();
    auto dir = [&](std::uint32_t j) { return glm::vec3(shape[j].x[lane], shape[j].y[lane], shape[j].z[lane]); };
    glm::vec3 d = dir(1);
    glm::vec3 e = anyPerpendicular(d);
    rest[0].lx[lane] = e.x;
    rest[0].ly[lane] = e.y;
    rest[0].lz[lane] = e.z;
    for (std::uint32_t j = 1; j < block.points; ++j) {
        const glm::vec3 r = dir(j);
        const glm::vec3 b = glm::cross(d, e);
        rest[j].lx[lane] = glm::dot(r, d);
        rest[j].ly[lane] = glm::dot(r, e);
        rest[j].lz[lane] = glm::dot(r, b);
        // Transport (d, e) onto r: the shortest rotation taking d to r.
        e = rotateShortestArc(d, r, e);
        e = glm::normalize(e - r * glm::dot(e, r));
        d = r;
    }
}

// Puts one lane's strand at its rest shape, at rest, in world space; its clearance becomes unknown.
void placeLaneAtRest(Solver::Block& block, int lane, const glm::mat3& rotation, const glm::vec3& translation)
{
    const RestRow* rest = block.rest.data();
    const ShapeRow* shape = block.shape.data();
    ParticleRow* row = block.state.data();
    glm::vec3 p = rotation * glm::vec3(shape[0].x[lane], shape[0].y[lane], shape[0].z[lane]) + translation;
    for (std::uint32_t j = 0; j < block.points; ++j) {
        if (j > 0)
            p += rotation * glm::vec3(shape[j].x[lane], shape[j].y[lane], shape[j].z[lane]) * rest[j].length[lane];
        row[j].x[lane] = row[j].px[lane] = p.x;
        row[j].y[lane] = row[j].py[lane] = p.y;
        row[j].z[lane] = row[j].pz[lane] = p.z;
        row[j].clearance[lane] = -1.0f;
    }
}

// Asks for row j of the block that follows this one in memory (blocks are laid out one after
// another and a thread runs a contiguous range of them): its first touches would otherwise stall
// the next block's serial chain on memory. A prefetch past the arrays' end is harmless.
inline void prefetchRows(const Solver::Block& block, std::uint32_t j)
{
    const auto ahead = [&](const auto* rows) {
        const char* at = reinterpret_cast<const char*>(rows) + (block.points + j) * sizeof(*rows);
        for (std::size_t byte = 0; byte < sizeof(*rows); byte += 64)
            __builtin_prefetch(at + byte);
    };
    ahead(block.state.data());
    ahead(block.rest.data());
}

// Substeps [firstSubstep, endSubstep) of the step; the last call of a step (endSubstep ==
// c.substeps) also puts back strands that went non-finite or flew away.
template <bool Transformed, bool GlobalShape>
void advanceBlock(Solver::Block& block, const StepConstants& c, int firstSubstep, int endSubstep)
{
    const std::uint32_t n = block.points;
    ParticleRow* row = block.state.data();
    const RestRow* rest = block.rest.data();
    const GlobalShapeRow* globalShape = block.globalShape.data(); // null while it is off

    // Roots in world space at the start and the end of this step; substeps interpolate between them.
    const V3 rootHead{ block.shape[0].x, block.shape[0].y, block.shape[0].z };
    const V3 rootEnd = Transformed ? transform(c.rotation, rootHead) + splat(c.translation) : rootHead;
    const V3 rootStart
        = Transformed ? transform(c.previousRotation, rootHead) + splat(c.previousTranslation) : rootHead;

    // Wind (eq. 1 and 2 of the force-driven hair paper) with gusts sampled at each particle, so
    // they vary along a strand (turbulence is ours).
    const V3 baseWind = splat(c.wind) + V3{ block.windX, block.windY, block.windZ };
    const float windSpeed = glm::length(c.wind);
    const bool gusty = c.turbulence > 0.0f && windSpeed > 0.0f;
    const Lane gustAmplitude = splat(c.turbulence * windSpeed);
    const float gustTime = static_cast<float>(std::fmod(c.time, 1000.0));

    const V3 gravityStep = splat(c.gravity * (c.dt * c.dt));
    const Lane dt = splat(c.dt), keep = splat(c.keep);
    const Lane drag = splat(c.drag) * block.dragScale;
    const Lane velocityCorrection = splat(c.velocityCorrection);
    // The bend's reaction on the parent (below) carries force up the strand through the parent's
    // Verlet velocity, which the next substep's predict damps (keep) and drags (1 / (1 + k dt)) as
    // if it were motion. Of the force that holds a resting lock up that takes a share which grows
    // with the substep, so a combed lock rested lower at fewer substeps than at more (issue 11: its
    // rest shape is solved at one substep count and the editor's pacer may run another). The
    // reaction is divided by that share here; capped, so strong drag or damping at a long substep
    // (where the share is no small correction) never amplifies it much.
    const Lane kickGain = lmin((splat(1.0f) + drag * dt) * splat(1.0f / c.keep), splat(kMaxKickGain));
    const ContactFriction mu{ splat(c.friction), splat(c.friction * kStaticOverKineticFriction) };

    // The capsules any particle of this block can reach this step: none farther from its root than
    // its strand is long (with a margin for what contact may have stretched), so a capsule beyond
    // that from every root is left out for the whole step, as the head is by its clearance bound.
    std::array<const Capsule*, 16> capsules{};
    std::size_t capsuleCount = 0;
    const bool filterCapsules = c.capsulesWorld.size() <= capsules.size();
    for (const Capsule& capsule : c.capsulesWorld) {
        if (!filterCapsules)
            break;
        const V3 a = splat(capsule.a);
        const glm::vec3 abv = capsule.b - capsule.a;
        const float ab2 = glm::dot(abv, abv);
        const V3 ab = splat(abv);
        const Lane u
            = ab2 > 0.0f ? lmin(lmax(dot(rootEnd - a, ab) * (1.0f / ab2), splat(0.0f)), splat(1.0f)) : splat(0.0f);
        const V3 away = rootEnd - (a + ab * u);
        const Lane reach = block.strandLength * 1.25f + (capsule.radiusMetres + c.offset + 0.02f);
        if (anyOf(dot(away, away) < reach * reach))
            capsules[capsuleCount++] = &capsule;
    }
    auto capsuleAt
        = [&](std::size_t k) -> const Capsule& { return filterCapsules ? *capsules[k] : c.capsulesWorld[k]; };
    const std::size_t capsulesToCheck = filterCapsules ? capsuleCount : c.capsulesWorld.size();

    // Verlet (eq. 3) with drag toward the wind taken implicitly: v' = (keep v + k dt w) / (1 + k dt)
    // + g dt, which only ever moves v toward w, so any drag at any step is stable, and leaves
    // gravity whole (hair at rest feels all its weight, whatever the drag and the step). k is the
    // drag scaled by eq. 1's s = |w x t| / (|w||t|): wind across the strand pushes, along it not.
    auto predict = [&](const V3& x, const V3& previous, const V3& parentBefore, const V3& gustHere) {
        V3 wind = baseWind;
        if (gusty)
            wind = wind + gustHere * gustAmplitude;
        const Lane windSpeed2 = dot(wind, wind);
        const Mask calm = windSpeed2 < splat(1e-12f);
        const V3 tangent = x - parentBefore;
        const Lane wt = dot(wind, tangent);
        const Lane invTangent = lrsqrt(lmax(dot(tangent, tangent), splat(1e-20f)));
        const Lane across2
            = splat(1.0f) - (wt * wt) * (invTangent * invTangent) * lrcp(select(calm, splat(1.0f), windSpeed2));
        const Lane across2Safe = lmax(across2, splat(1e-20f));
        const Lane across = select(calm, splat(1.0f), across2Safe * lrsqrt(across2Safe));
        const Lane kdt = drag * across * dt;
        const V3 move = (x - previous) * keep + wind * (kdt * dt);
        return x + move * lrcp(splat(1.0f) + kdt) + gravityStep;
    };

    // Length, then contact, for particle i whose bent position is `bent` and whose parent is final
    // at `parent`: follow the leader (Müller et al. 2012) puts it at rest length from its parent,
    // then the head field and the capsules push it out (keeping that length where they can), and
    // the DFTL velocity correction (eq. 9: v_{i-1} -= s d_i / dt, in Verlet form the parent's
    // previous position moves by s d_i) damps what the length projection added. `reach` is the
    // bent position less the parent's, `before` the particle's position at the start of the
    // substep, `kick` the bend's reaction on the parent (added to its previous position with the
    // DFTL correction, one write). Returns its final position.
    auto finish = [&](std::uint32_t i, const V3& before, const V3& reach, const V3& parent, const V3& kick,
                      Lane inverseLength) {
        ParticleRow& p = row[i];
        V3 previous = before;
        const Lane length = rest[i].length;
        const Lane scale = length * lrsqrt(lmax(dot(reach, reach), splat(1e-24f)));
        V3 position = parent + reach * scale;
        const V3 correction = reach * (scale - 1.0f); // position - bent
        bool looked = false; // whether contact may have moved it (else `checked` is final)

        // The field lookup is most of a step's cost (memory latency), so it is skipped while the
        // clearance bound says no lane can touch: the bound shrinks by each move's L1 length,
        // which is never less than its true length.
        const V3 checked = position;
        Lane clearance = p.clearance - l1Length(position - before);
        if (c.field && (Transformed || anyOf(clearance < splat(0.0f)))) {
            // The head's distance and normal at a world-space position.
            auto sampleHead = [&](const V3& at) {
                SdfSample sample = sampleField(
                    *c.field, Transformed ? transform(glm::transpose(c.rotation), at - splat(c.translation)) : at);
                if (Transformed)
                    sample.normal = transform(c.rotation, sample.normal);
                return sample;
            };
            const SdfSample sample = sampleHead(position);
            const Lane depth = splat(c.offset) - sample.distance;
            const Mask inside = depth > splat(0.0f);
            if (anyOf(inside)) {
                // A curved surface is not its tangent plane: turn onto the plane, look again from
                // there, and only then push what the segment cannot reach.
                resolveContact(inside, depth, sample.normal, mu, parent, length, inverseLength, before, position,
                    previous, false, splat(c.offset));
                // What is left within half the offset (still clear of the skin) stays: turning it
                // far along the arc below for that little would shake stiff hair lying on the head.
                const Lane slack = select(length < splat(2.0f * c.offset), splat(c.offset), splat(0.5f * c.offset));
                for (int pass = 1; pass <= kHeadContactPasses; ++pass) {
                    const SdfSample next = sampleHead(position);
                    const Lane nextDepth = splat(c.offset) - next.distance;
                    const Mask stillInside = nextDepth > splat(0.0f);
                    const Mask stuck = stillInside & (nextDepth > slack);
                    if (!anyOf(pass < kHeadContactPasses ? stillInside : stuck))
                        break;
                    if (pass < kHeadContactPasses) {
                        resolveContact(stillInside, nextDepth, next.normal, mu, parent, length, inverseLength, before,
                            position, previous, false, splat(c.offset));
                        // Turning converges fast on a smooth surface: look once more only where a
                        // lane was still a quarter of the offset deep before this last turn (in a
                        // crevice the last turn may put it deeper on the other wall).
                        if (pass + 1 == kHeadContactPasses && !anyOf(stillInside & (nextDepth > slack * 0.5f)))
                            break;
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
                        applyFriction(arcClears, nextDepth, next.normal, mu, before, position, previous);
                    }
                    resolveContact(stuck & ~arcClears, nextDepth, next.normal, mu, parent, length, inverseLength,
                        before, position, previous, true, splat(c.offset));
                }
            }
            // A moving head moves the field under the particles: no bound survives that.
            clearance = Transformed ? splat(-1e30f) : lmax(-depth, splat(0.0f));
            looked = true;
        }
        for (std::size_t k = 0; k < capsulesToCheck; ++k) {
            const Capsule& capsule = capsuleAt(k);
            const V3 a = splat(capsule.a);
            const glm::vec3 abv = capsule.b - capsule.a;
            const float ab2 = glm::dot(abv, abv);
            const V3 ab = splat(abv);
            const Lane u
                = ab2 > 0.0f ? lmin(lmax(dot(position - a, ab) * (1.0f / ab2), splat(0.0f)), splat(1.0f)) : splat(0.0f);
            const V3 away = position - (a + ab * u);
            const Lane dist = lsqrt(dot(away, away));
            const Lane depth = splat(capsule.radiusMetres + c.offset) - dist;
            const Mask inside = (depth > splat(0.0f)) & (dist > splat(1e-9f));
            if (anyOf(inside)) {
                const V3 normal = away * (splat(1.0f) / lmax(dist, splat(1e-9f)));
                resolveContact(inside, depth, normal, mu, parent, length, inverseLength, before, position, previous,
                    true, splat(c.offset));
                looked = true;
            }
        }
        if (i > 1) {
            ParticleRow& q = row[i - 1];
            q.px += kick.x + velocityCorrection * correction.x;
            q.py += kick.y + velocityCorrection * correction.y;
            q.pz += kick.z + velocityCorrection * correction.z;
        }
        // (Where nothing looked, position is `checked` and the bound stands as it is.)
        p.clearance = looked ? clearance - l1Length(position - checked) : clearance;
        p.x = position.x;
        p.y = position.y;
        p.z = position.z;
        p.px = previous.x;
        p.py = previous.y;
        p.pz = previous.z;
        return position;
    };

    for (int s = firstSubstep; s < endSubstep; ++s) {
        const Lane t = splat(static_cast<float>(s + 1) / static_cast<float>(c.substeps));
        const V3 root = rootStart + (rootEnd - rootStart) * t;
        V3 parentBefore{ row[0].x, row[0].y, row[0].z };
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
        V3 frameD{ block.shape[1].x, block.shape[1].y,
            block.shape[1].z }; // the follicle's frame: the root segment's rest
        V3 frameE{ rest[0].lx, rest[0].ly, rest[0].lz }; // direction and a normal to it
        if (Transformed) {
            frameD = transform(c.rotation, frameD);
            frameE = transform(c.rotation, frameE);
        }
        V3 frameB = cross(frameD, frameE);
        // The target direction of segment j: its rest direction's coordinates in the parent's rest
        // frame, laid on the parent's frame now.
        V3 turned = frameD * rest[1].lx + frameE * rest[1].ly + frameB * rest[1].lz;
        for (std::uint32_t j = 1; j < n; ++j) {
            ParticleRow& p = row[j];
            const RestRow& r = rest[j];
            if (s
                == firstSubstep) // the next block's rows (the next in memory, which this thread most likely runs next)
                prefetchRows(block, j);
            const V3 x{ p.x, p.y, p.z };
            // Gusts are smooth over tens of centimetres: sampled at every kGustStride-th particle
            // (where the particles were at the start of the substep) and interpolated between.
            V3 gustHere{};
            if (gusty) {
                const std::uint32_t k = (j - 1) % kGustStride;
                if (k == 0) {
                    const std::uint32_t ahead = std::min(j + kGustStride, n - 1);
                    gustFrom = j == 1 ? gust(x, gustTime) : gustTo;
                    gustTo = ahead == j ? gustFrom : gust(V3{ row[ahead].x, row[ahead].y, row[ahead].z }, gustTime);
                    gustSpan = splat(1.0f / static_cast<float>(std::max<std::uint32_t>(ahead - j, 1)));
                }
                gustHere = gustFrom + (gustTo - gustFrom) * (splat(static_cast<float>(k)) * gustSpan);
            }
            const V3 predicted = predict(x, V3{ p.px, p.py, p.pz }, parentBefore, gustHere);
            parentBefore = x;

            // Spring toward the target and damper on the particle's motion relative to its parent:
            //   Δx_j = (parent + turned L - predicted) child - ((predicted - x) - (parent - parentStart)) damping,
            // and the bent position less the parent's, written so that only `turned` and `parent`
            // wait on the chain:
            //   bent - parent = [predicted (1 - child) - (predicted - x) damping - parentStart damping]
            //                   + parent (damping + child - 1) + turned (L child).
            const Lane child = r.bendChild, damping = r.bendDamping;
            const V3 besideChain = predicted * (1.0f - child) - (predicted - x) * damping - parentStart * damping;
            V3 reach = besideChain + parent * (damping + child - 1.0f) + turned * (r.length * child);
            // The parent's equal and opposite momentum, as a velocity (DFTL's way): Δx_j m_j / m_{j-1},
            // made up for the damping and drag that the next substep applies to it (kickGain).
            const V3 kick = (parent + reach - predicted) * (r.bendParentRatio * kickGain);
            if constexpr (GlobalShape)
                reach = pullTowardGlobalShape<Transformed>(parent + reach, globalShape[j], root, rootHead, c.rotation)
                    - parent;
            parentStart = x;
            const Lane inverseLength = 1.0f / r.length;
            const V3 position = finish(j, x, reach, parent, kick, inverseLength);
            if (j + 1 < n) {
                // Transport the frame onto this segment's direction d now: the shortest rotation
                // from D to d takes a vector v across D to v - (d.v) / (1 + D.d) (D + d), which
                // keeps it unit and across d; E, B and the next target's part across D, w, are
                // such vectors. So the next target d lx + w - (d.w) / (1 + D.d) (D + d) waits only
                // for d, not for the new frame. (The reciprocal estimate is one Newton step from
                // exact; no renormalisation on the chain.)
                const RestRow& next = rest[j + 1];
                const V3 w = frameE * next.ly + frameB * next.lz;
                const V3 d = (position - parent) * inverseLength;
                const Lane inverse = lrcp(lmax(splat(1.0f) + dot(frameD, d), splat(1e-2f)));
                const V3 sum = frameD + d;
                turned = d * next.lx + w - sum * (dot(d, w) * inverse);
                frameE = frameE - sum * (dot(d, frameE) * inverse);
                frameB = frameB - sum * (dot(d, frameB) * inverse);
                frameD = d;
            }
            parent = position;
        }
    }

    if (endSubstep != c.substeps)
        return;
    // A strand that went non-finite or flew away is put back at rest. Strands interact only through
    // the volume grid, which reads a non-finite particle as outside it, so it does not spread.
    Lane farthest = splat(0.0f);
    Mask finite = Mask{} == 0;
    for (std::uint32_t j = 0; j < n; ++j) {
        const V3 x{ row[j].x, row[j].y, row[j].z };
        const V3 pv{ row[j].px, row[j].py, row[j].pz };
        const V3 d = x - rootEnd;
        farthest = lmax(farthest, dot(d, d));
        const V3 m = x - pv;
        finite &= dot(m, m) < splat(1e12f); // false for NaN
    }
    const Lane limit = block.strandLength * 1.5f + 0.05f;
    const Mask bad = ~((farthest < limit * limit) & finite);
    if (anyOf(bad)) {
        for (int l = 0; l < kLanes; ++l) {
            if (!bad[l])
                continue;
            placeLaneAtRest(block, l, c.rotation, c.translation);
            if (block.strand[l] >= 0)
                __atomic_fetch_add(c.resetCounter, 1, __ATOMIC_RELAXED);
        }
    }
}

} // namespace

Solver::Solver(int threadCount)
    : m_pool(std::make_unique<ThreadPool>(threadCount))
{
}
Solver::~Solver() = default;

int Solver::threadCount() const
{
    return m_pool->threadCount();
}

std::string Solver::setStrands(const HairCurves& rest)
{
    if (rest.offsets.empty() || rest.offsets.front() != 0 || rest.offsets.back() != rest.positions.size())
        return "strands: the offsets do not match the points";
    // Group strands by particle count: a block's 8 lanes must run the same loop.
    std::map<std::uint32_t, std::vector<std::uint32_t>> byCount;
    for (std::size_t i = 0; i < rest.strandCount(); ++i) {
        const std::span<const glm::vec3> s = rest.strand(i);
        if (s.size() < 2)
            return "strand " + std::to_string(i) + ": has " + std::to_string(s.size())
                + " points; at least 2 are needed";
        for (std::size_t j = 0; j < s.size(); ++j) {
            if (!std::isfinite(s[j].x) || !std::isfinite(s[j].y) || !std::isfinite(s[j].z))
                return "strand " + std::to_string(i) + ": point " + std::to_string(j) + " is not finite";
            if (j > 0 && !(glm::distance(s[j], s[j - 1]) > 1e-7f))
                return "strand " + std::to_string(i) + ": points " + std::to_string(j - 1) + " and " + std::to_string(j)
                    + " coincide (zero-length segment)";
        }
        byCount[static_cast<std::uint32_t>(s.size())].push_back(static_cast<std::uint32_t>(i));
    }

    std::size_t rows = 0;
    for (const auto& [count, strands] : byCount)
        rows += count * ((strands.size() + kLanes - 1) / kLanes);
    std::vector<ParticleRow> stateRows(rows);
    std::vector<RestRow> restRows(rows);
    std::vector<ShapeRow> shapeRows(rows);
    std::vector<Block> blocks;
    std::size_t particles = 0;
    std::size_t nextRow = 0;
    for (const auto& [count, strands] : byCount) {
        for (std::size_t first = 0; first < strands.size(); first += kLanes) {
            Block b;
            b.points = count;
            b.state = std::span<ParticleRow>(stateRows.data() + nextRow, count);
            b.rest = std::span<RestRow>(restRows.data() + nextRow, count);
            b.shape = std::span<ShapeRow>(shapeRows.data() + nextRow, count);
            nextRow += count;
            for (int l = 0; l < kLanes; ++l) {
                // Padding lanes repeat the block's first strand and are never copied out.
                const bool real = first + static_cast<std::size_t>(l) < strands.size();
                const std::uint32_t strand = strands[real ? first + static_cast<std::size_t>(l) : first];
                b.strand[l] = real ? static_cast<std::int64_t>(strand) : -1;
                const std::span<const glm::vec3> s = rest.strand(strand);
                float total = 0.0f;
                for (std::uint32_t j = 0; j < count; ++j) {
                    RestRow& r = b.rest[j];
                    ShapeRow& q = b.shape[j];
                    if (j == 0) {
                        q.x[l] = s[0].x;
                        q.y[l] = s[0].y;
                        q.z[l] = s[0].z;
                        r.length[l] = 0.0f;
                    } else {
                        const glm::vec3 d = s[j] - s[j - 1];
                        const float len = glm::length(d);
                        q.x[l] = d.x / len;
                        q.y[l] = d.y / len;
                        q.z[l] = d.z / len;
                        r.length[l] = len;
                        total += len;
                    }
                }
                b.strandLength[l] = total;
                storeRestFrames(b, l);
                b.stiffnessScale[l] = 1.0f;
                b.dragScale[l] = 1.0f;
                b.volumeWeight[l] = real ? total / static_cast<float>(count - 1) : 0.0f;
                b.volumeTargetScale[l] = 1.0f;
            }
            particles += count * std::min<std::size_t>(kLanes, strands.size() - first);
            blocks.push_back(std::move(b));
        }
    }
    m_blocks = std::move(blocks);
    m_stateRows = std::move(stateRows); // moving keeps the buffers, so the blocks' views stay valid
    m_restRows = std::move(restRows);
    m_shapeRows = std::move(shapeRows);
    m_slotOfStrand.assign(rest.strandCount(), {});
    for (std::uint32_t i = 0; i < m_blocks.size(); ++i)
        for (std::uint32_t l = 0; l < kLanes; ++l)
            if (m_blocks[i].strand[l] >= 0)
                m_slotOfStrand[static_cast<std::size_t>(m_blocks[i].strand[l])] = { i, l };
    m_restOffsets = rest.offsets;
    m_bendSharesStale = true;
    m_globalShapeStale = true;
    m_globalShapeRows.clear();
    m_strandCount = rest.strandCount();
    m_particleCount = particles;
    m_scalpArea = 0.0f;
    updateVolumeBounds();
    resetToRest();
    return {};
}

namespace {

// The scalp area the simulated roots cover, m², when nobody said: the cells of a 1 cm grid that
// hold a root, each about 1 cm² / 1.5 of surface (a plane cuts 1.5 cells per cell area on average).
float estimatedScalpArea(std::span<const Solver::Block> blocks)
{
    constexpr float kCell = 0.01f;
    std::vector<std::int64_t> cells;
    for (const Solver::Block& b : blocks)
        for (int l = 0; l < kLanes; ++l)
            if (b.strand[l] >= 0) {
                const glm::ivec3 c(glm::floor(glm::vec3(b.shape[0].x[l], b.shape[0].y[l], b.shape[0].z[l]) / kCell));
                cells.push_back((static_cast<std::int64_t>(c.x & 0x1FFFFF) << 42)
                    | (static_cast<std::int64_t>(c.y & 0x1FFFFF) << 21) | (c.z & 0x1FFFFF));
            }
    std::sort(cells.begin(), cells.end());
    const auto distinct = std::unique(cells.begin(), cells.end()) - cells.begin();
    return static_cast<float>(distinct) * kCell * kCell / 1.5f;
}

} // namespace

// The head-space box every particle stays in (its root's box grown by its strand's length), and
// the hair per scalp area from the particles' weights.
void Solver::updateVolumeBounds()
{
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    double hair = 0.0;
    for (const Block& b : m_blocks)
        for (int l = 0; l < kLanes; ++l) {
            if (b.strand[l] < 0)
                continue;
            const glm::vec3 root(b.shape[0].x[l], b.shape[0].y[l], b.shape[0].z[l]);
            lo = glm::min(lo, root - b.strandLength[l]);
            hi = glm::max(hi, root + b.strandLength[l]);
            hair += static_cast<double>(b.volumeWeight[l]) * (b.points - 1);
        }
    m_volumeLo = lo;
    m_volumeHi = hi;
    m_volumeUnitsStale = true; // the weights changed: the grid's fixed point is set on the next pass
    if (!(m_scalpArea > 0.0f))
        m_scalpArea = estimatedScalpArea(m_blocks);
    m_hairPerScalpArea = m_scalpArea > 0.0f ? static_cast<float>(hair / m_scalpArea) : 0.0f;
    // A regroom (a brush dab) barely moves the box: the grid is kept while the new box fits in it
    // and fills at least half of it; laying it out again (32 MiB and the head's solid) costs about
    // 0.3 s, far more than a dab.
    if (m_volumeGrid && !m_volumeGrid->empty()) {
        const glm::vec3 gridLo = m_volumeGrid->origin();
        const glm::vec3 gridHi = gridLo + m_volumeGrid->cellMetres() * glm::vec3(m_volumeGrid->dims() - 1);
        const glm::vec3 size = glm::max(hi - lo, glm::vec3(0.0f)), gridSize = gridHi - gridLo;
        const bool fits = glm::all(glm::greaterThanEqual(lo, gridLo)) && glm::all(glm::lessThanEqual(hi, gridHi));
        if (fits && size.x * size.y * size.z >= 0.5f * gridSize.x * gridSize.y * gridSize.z)
            return;
    }
    m_volumeGrid.reset(); // laid out again on the next step with volume on
}

float Solver::volumeTargetDensity() const
{
    return m_settings.volume > 0.0f ? m_hairPerScalpArea / (m_settings.volume * kVolumeDepthMetres) : 0.0f;
}

std::string Solver::setStrandVolume(std::span<const float> drawnStrands, float scalpAreaSquareMetres)
{
    if (!drawnStrands.empty() && drawnStrands.size() != m_strandCount)
        return "drawn strands: " + std::to_string(drawnStrands.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    for (std::size_t i = 0; i < drawnStrands.size(); ++i)
        if (!(drawnStrands[i] >= 0.0f && drawnStrands[i] <= 1e6f))
            return "drawn strands of strand " + std::to_string(i) + ": " + std::to_string(drawnStrands[i])
                + " is not a finite number of at least 0";
    if (!(scalpAreaSquareMetres >= 0.0f && scalpAreaSquareMetres <= 1e4f))
        return "scalp area: " + std::to_string(scalpAreaSquareMetres) + " m² is not a finite area of at least 0";
    for (std::size_t i = 0; i < m_strandCount; ++i) {
        const Slot slot = m_slotOfStrand[i];
        Block& b = m_blocks[slot.block];
        const float drawn = drawnStrands.empty() ? 1.0f : drawnStrands[i];
        b.volumeWeight[slot.lane] = drawn * b.strandLength[slot.lane] / static_cast<float>(b.points - 1);
    }
    m_scalpArea = scalpAreaSquareMetres;
    updateVolumeBounds();
    return {};
}

std::string Solver::setVolumeTargetScales(std::span<const float> perStrand)
{
    if (!perStrand.empty() && perStrand.size() != m_strandCount)
        return "volume target scales: " + std::to_string(perStrand.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    for (std::size_t i = 0; i < perStrand.size(); ++i)
        if (!(perStrand[i] >= 0.01f && perStrand[i] <= 1e3f))
            return "volume target scale of strand " + std::to_string(i) + ": " + std::to_string(perStrand[i])
                + " is not a finite number within 0.01..1000";
    for (std::size_t i = 0; i < m_strandCount; ++i) {
        const Slot slot = m_slotOfStrand[i];
        m_blocks[slot.block].volumeTargetScale[slot.lane] = perStrand.empty() ? 1.0f : perStrand[i];
    }
    return {};
}

// How hard hair denser than its target pushes down the density gradient: the acceleration is this
// times (density / target - 1, at most 1) times the gradient of density / target (1/m), so hair at
// twice its target that thins out over 2 cm pushes at 200 m/s² before the cap. Capped at
// kVolumeMaxAcceleration (3 g) so a particle deep in a knot is not flung. Measured on the default
// groom (tests/sim/VolumeTest.cpp): 1 m²/s² leaves the top at 8 mm, 4 gives 18 mm, 10 gives 20 mm.
constexpr float kVolumeStiffness = 4.0f; // m²/s²
constexpr float kVolumeMaxAcceleration = 30.0f; // m/s²
// The push's stiffness is at most this times (cell / substep)², measured: 1 substep at 60 Hz with
// 8 segments leaves 0 % of tips moving at 0.6 (VolumeTest's settling cases).
constexpr float kVolumeStableShare = 0.6f;
// Damping of the motion along the push where hair is denser than its target, per second: the share
// 1 - exp(-this dt) of it is taken each substep (the same at any substep count).
constexpr float kVolumeDampingPerSecond = 30.0f;
// The grid is laid again after at least this long of substeps (Solver::step): 1/120 s, the default
// substep (two at 60 Hz), so the default scene lays it every substep.
constexpr float kVolumeRefreshSeconds = 1.0f / 120.0f;
// A particle that moved this far in one substep (or went non-finite) is left out of the grid.
constexpr float kVolumeMaxMoveMetres = 0.5f;

// One substep's hair-hair interaction, before the blocks advance (so contact, after it, stays the
// last word): every particle splats its weight and its move over the last substep into the grid;
// then each particle's velocity is blended toward the hair's mean velocity there by the hair
// friction (PIC/FLIP-style, Petrovic et al. 2005 sec. 4; McAdams et al. 2009), and where the
// density is above the target the particle is accelerated down the density gradient (the hair's
// own volume: Petrovic et al.'s pressure term, here only above the target, so hair at or below
// its volume feels nothing). Both change only the previous position (the velocity): the position
// is as the last substep left it, so length and contact stay as they were.
int Solver::volumeRefreshSubsteps(float substepSeconds)
{
    return std::max(1, static_cast<int>(kVolumeRefreshSeconds / substepSeconds + 1e-3f));
}

// A row's sixteen strands lie side by side on the scalp. Where a dense groom puts them much closer
// than a cell (groom-1m: 1-3 mm apart in 2 cm cells), the grid cannot tell them apart: only every
// stride-th strand splats, with the weight of those it stands for, and is sampled; the strands
// between blend the samples around them (HairVolumeGrid::sampleRow), as members follow their key.
// The stride is the largest power of two whose sampled strands are within kVolumeLodCellShare of a
// cell of each other everywhere along them, where they are now (Solver::volumeSplat); 1 for a
// block with padding, and in practice for the editor's keys (5-10 mm apart in 8-15 mm cells).
constexpr float kVolumeLodCellShare = 0.5f;
// The grid's nodes (HairVolumeGrid::setBounds) for a scene of `particles`: all the memory bound
// allows up to kVolumeFullGridParticles, and fewer in proportion beyond (a quarter at a million,
// cells 1.6 times as wide): the splat and the read wait on cache misses in a grid much larger than
// the cache, and a dense groom has hair enough in every cell of the coarser grid.
constexpr std::size_t kVolumeFullGridParticles = 250'000;
std::size_t volumeGridNodes(std::size_t particles)
{
    return particles <= kVolumeFullGridParticles
        ? HairVolumeGrid::kMaxNodes
        : static_cast<std::size_t>(static_cast<double>(HairVolumeGrid::kMaxNodes)
            * (static_cast<double>(kVolumeFullGridParticles) / static_cast<double>(particles)));
}

int Solver::volumeStrideOfStrand(std::size_t strand) const
{
    return strand < m_slotOfStrand.size() ? m_blocks[m_slotOfStrand[strand].block].volumeStride : 0;
}

void Solver::volumePass(const StepConstants& c, int substepsUntilNext)
{
    if (!m_volumeGrid) {
        m_volumeGrid = std::make_unique<HairVolumeGrid>();
        m_volumeUnitsStale = true;
        if (m_volumeGrid->setBounds(m_volumeLo, m_volumeHi, threadCount(), volumeGridNodes(m_particleCount)) && m_sdf)
            m_volumeGrid->setSolid([&](const glm::vec3& p) { return m_sdf->distance(p); });
    }
    HairVolumeGrid& grid = *m_volumeGrid;
    if (grid.empty())
        return;
    if (m_volumeUnitsStale) {
        double total = 0.0; // the most weight a pass splats: every particle's
        for (const Block& b : m_blocks)
            for (int l = 0; l < kLanes; ++l)
                total += static_cast<double>(b.volumeWeight[l]) * b.points;
        grid.clear(nullptr);
        grid.setWeightBound(total);
        m_volumeSplatted = false;
        m_volumeUnitsStale = false;
    }
    ++m_volumePasses;
    // Few particles (the editor's keys): the calling thread does it all; waking the pool for each of
    // the pass's loops would cost more than they do.
    constexpr std::size_t kParallelVolumeParticles = 50'000;
    ThreadPool* pool = m_particleCount >= kParallelVolumeParticles ? m_pool.get() : nullptr;
    // The blocks splatted their end state at the end of the last run of substeps (step()); only
    // when something moved particles since (or there was no run) do they splat here, in a sweep.
    if (!m_volumeSplatted) {
        grid.clear(pool);
        auto splatBlocks = [&](std::size_t begin, std::size_t end) {
            const int slot = grid.claimSlot();
            for (std::size_t i = begin; i < end; ++i)
                volumeSplat(m_blocks[i], c, slot);
            grid.releaseSlot(slot);
        };
        if (pool)
            pool->parallelFor(m_blocks.size(), 4, splatBlocks);
        else
            splatBlocks(0, m_blocks.size());
    }
    m_volumeSplatted = false;
    VolumeRead& v = m_volumeRead;
    v.target = volumeTargetDensity();
    grid.finish(pool, v.target);

    // The share of the difference from the hair's mean velocity lost this substep: hair_friction
    // is the share lost per 1/60 s, the same at any substep.
    v.blend = 1.0f - std::pow(1.0f - m_settings.hairFriction, c.dt * 60.0f);
    // The push is a stiff spring taken explicitly: past about (cell / dt)² it overshoots and hair
    // bounces on hair (one substep at 60 Hz did, 22 % of tips moving after 10 s), so its stiffness
    // is capped there; at the default two substeps the cap is about 2 m²/s².
    // (The grid is read for substepsUntilNext substeps: the spring's step is that long.)
    const float cell = grid.cellMetres();
    const float refreshSeconds = c.dt * static_cast<float>(substepsUntilNext);
    v.stiffness = std::min(kVolumeStiffness, kVolumeStableShare * cell * cell / (refreshSeconds * refreshSeconds));
    v.pushDamping = 1.0f - std::exp(-kVolumeDampingPerSecond * c.dt);
}

// One block's splat into the grid's slot `slot`, row by row (a row's strands lie side by side):
// each particle's weight and its move over the last substep, at its head-space position.
void Solver::volumeSplat(Block& b, const StepConstants& c, int slot)
{
    HairVolumeGrid& grid = *m_volumeGrid;
    const glm::mat3 toHead = glm::transpose(c.rotation);
    // The level of detail (kVolumeLodCellShare): how far apart neighbouring lanes are now.
    bool full = true;
    for (int l = 0; l < kLanes; ++l)
        full = full && b.strand[l] >= 0;
    int stride = 1;
    if (full) {
        using LaneIndex = int __attribute__((vector_size(kLanes * sizeof(int))));
        const LaneIndex next{ 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 15 };
        Lane farthest2{};
        for (std::uint32_t j = 1; j < b.points; ++j) {
            const ParticleRow& r = b.state[j];
            const Lane dx = __builtin_shuffle(r.x, next) - r.x, dy = __builtin_shuffle(r.y, next) - r.y,
                       dz = __builtin_shuffle(r.z, next) - r.z;
            farthest2 = lmax(farthest2, dx * dx + dy * dy + dz * dz);
        }
        float spacing2 = 0.0f;
        for (int l = 0; l < kLanes; ++l)
            spacing2 = std::max(spacing2, farthest2[l]); // NaN (a broken strand) leaves it, stride 1 below
        const float reach = kVolumeLodCellShare * grid.cellMetres();
        while (stride < kLanes && 4.0f * static_cast<float>(stride * stride) * spacing2 <= reach * reach
            && std::isfinite(spacing2))
            stride *= 2;
    }
    b.volumeStride = stride;
    Lane groupWeight = splat(0.0f); // at each group's first lane, the weight of its lanes
    for (int l = 0; l < kLanes; ++l)
        groupWeight[l - l % stride] += b.volumeWeight[l];
    for (std::uint32_t j = 0; j < b.points; ++j) {
        const ParticleRow& r = b.state[j];
        const V3 x{ r.x, r.y, r.z };
        const V3 move = x - V3{ r.px, r.py, r.pz };
        // A particle gone non-finite or flying off (its strand is put back at rest at the end of
        // the step) must not spread through the grid.
        const Lane weight = select(l1Length(move) < kVolumeMaxMoveMetres, groupWeight, splat(0.0f));
        const V3 head = c.transformed ? transform(toHead, x - splat(c.translation)) : x;
        grid.splatRow(slot, reinterpret_cast<const float*>(&head.x), reinterpret_cast<const float*>(&head.y),
            reinterpret_cast<const float*>(&head.z), reinterpret_cast<const float*>(&weight),
            reinterpret_cast<const float*>(&move.x), reinterpret_cast<const float*>(&move.y),
            reinterpret_cast<const float*>(&move.z), HairVolumeGrid::kRowLanes, b.volumeStride);
    }
}

// The read of volumePass's grid for one block, all 16 lanes at once: each particle's velocity is
// blended toward the hair's mean velocity there by the hair friction, and where the density is
// above the target it is accelerated down the density gradient (see volumePass).
void Solver::volumeRead(Block& b, const StepConstants& c) const
{
    const HairVolumeGrid& grid = *m_volumeGrid;
    const VolumeRead& v = m_volumeRead;
    const Lane keep = v.target * b.volumeTargetScale;
    const Lane inverseKeep = splat(1.0f) / keep;
    const glm::mat3 toHead = glm::transpose(c.rotation);
    const float dt2 = c.dt * c.dt;
    HairVolumeGrid::SampleRow here;
    auto lane = [](const float* p) {
        Lane l;
        std::memcpy(&l, p, sizeof l);
        return l;
    };
    for (std::uint32_t j = 1; j < b.points; ++j) { // roots are pinned
        ParticleRow& r = b.state[j];
        const V3 x{ r.x, r.y, r.z };
        const V3 head = c.transformed ? transform(toHead, x - splat(c.translation)) : x;
        grid.sampleRow(reinterpret_cast<const float*>(&head.x), reinterpret_cast<const float*>(&head.y),
            reinterpret_cast<const float*>(&head.z), here, HairVolumeGrid::kRowLanes, b.volumeStride);
        const Lane density = lane(here.density);
        const Mask inHair = density > 0.0f;
        if (!anyOf(inHair))
            continue;
        V3 move = x - V3{ r.px, r.py, r.pz };
        const Lane hair = lane(here.hair);
        const Mask hasHair = hair > 0.0f;
        const Lane inverseHair = select(hasHair, splat(1.0f) / hair, splat(0.0f));
        const V3 mean = V3{ lane(here.momentumX), lane(here.momentumY), lane(here.momentumZ) } * inverseHair;
        move = select(hasHair, move + (mean - move) * splat(v.blend), move);
        const Lane excess = density * inverseKeep - 1.0f;
        const Mask pushing = excess > 0.0f;
        if (anyOf(pushing)) {
            V3 push = V3{ lane(here.gradX), lane(here.gradY), lane(here.gradZ) }
                * ((-v.stiffness) * lmin(excess, splat(1.0f)) * inverseKeep);
            const Lane length = lsqrt(dot(push, push));
            push = push * select(length > kVolumeMaxAcceleration, kVolumeMaxAcceleration / length, splat(1.0f));
            if (c.transformed)
                push = transform(c.rotation, push);
            // Pressure alone makes hair bounce on the hair beneath it (a stiff spring taken
            // explicitly): the motion along the push is damped where it pushes.
            const Mask along = pushing & (length > 0.0f);
            const V3 direction = select(along, V3{ push.x / length, push.y / length, push.z / length }, V3{});
            const V3 damped = move - direction * (v.pushDamping * dot(move, direction));
            move = select(pushing, damped + push * splat(dt2), move);
        }
        const V3 now = select(inHair, x - move, V3{ r.px, r.py, r.pz });
        r.px = now.x;
        r.py = now.y;
        r.pz = now.z;
    }
}

std::string Solver::setSettings(const SolverSettings& settings)
{
    std::string error = validateSolverSettings(settings);
    if (!error.empty())
        return error;
    if (settings.hairOffsetMetres != m_settings.hairOffsetMetres) // clearances are measured from the offset
        for (Block& b : m_blocks)
            for (ParticleRow& row : b.state)
                row.clearance = splat(-1.0f);
    m_settings = settings;
    return {};
}

void Solver::setCollider(std::shared_ptr<const SignedDistanceField> headSdf)
{
    m_sdf = headSdf && !headSdf->empty() ? std::move(headSdf) : nullptr;
    m_field = m_sdf ? std::make_unique<CollisionField>(*m_sdf) : nullptr;
    m_volumeGrid.reset(); // its solid is the head
    for (Block& b : m_blocks)
        for (ParticleRow& row : b.state)
            row.clearance = splat(-1.0f);
}

void Solver::setCapsules(std::vector<Capsule> capsules)
{
    m_capsules = std::move(capsules);
}

void Solver::setHeadTransform(const glm::mat4& headToWorld)
{
    m_headToWorld = headToWorld;
}

void Solver::resetToRest()
{
    m_volumeSplatted = false; // the grid's last splats are of the old state
    m_previousHeadToWorld = m_headToWorld;
    const glm::mat3 rotation(m_headToWorld);
    const glm::vec3 translation(m_headToWorld[3]);
    for (Block& b : m_blocks)
        for (int l = 0; l < kLanes; ++l)
            placeLaneAtRest(b, l, rotation, translation);
}

// The bend shares of every segment for a substep of `substepSeconds` (BendingModel.h): from the
// rigidity of each lane's stiffness (settings x the strand's scale) and the segment lengths.
void Solver::updateBendShares(float substepSeconds)
{
    const float globalStiffness = m_settings.stiffness;
    if (m_bendSharesFor == glm::vec2(globalStiffness, substepSeconds) && !m_bendSharesStale)
        return;
    m_bendSharesFor = { globalStiffness, substepSeconds };
    m_bendSharesStale = false;
    m_pool->parallelFor(m_blocks.size(), 16, [&](std::size_t begin, std::size_t end) {
        std::vector<float> lengths;
        for (std::size_t i = begin; i < end; ++i) {
            const Block& b = m_blocks[i];
            const int n = static_cast<int>(b.points);
            lengths.resize(b.points);
            for (int l = 0; l < kLanes; ++l) {
                const float rigidity = bending::rigidity(std::min(1.0f, globalStiffness * b.stiffnessScale[l]));
                for (int j = 0; j < n; ++j)
                    lengths[j] = b.rest[j].length[l];
                for (int j = 1; j < n; ++j) {
                    const bending::Constraint k = bending::constraint(rigidity, substepSeconds, lengths.data(), n, j);
                    RestRow& r = b.rest[j];
                    r.bendChild[l] = k.child;
                    r.bendDamping[l] = k.damping;
                    r.bendParentRatio[l] = k.parentRatio;
                }
            }
        }
    });
}

// The global shape's rows for a substep of `substepSeconds` (pullTowardGlobalShape): each
// particle's rest position, and its share s_j = 1 - (1 - g f_j)^(dt / kGlobalShapeStepSeconds),
// which moves as far per second at any substep count (as damping's exp(-k dt) does), with
// f_j = max(0, 1 - u_j / kGlobalShapeReach) at u_j, the rest arc length from the root over the
// strand's. None while the global shape is 0: the step then reads nothing more.
void Solver::updateGlobalShape(float substepSeconds)
{
    const float g = m_settings.globalShape;
    if (!(g > 0.0f)) {
        if (!m_globalShapeRows.empty()) {
            m_globalShapeRows = {};
            for (Block& b : m_blocks)
                b.globalShape = {};
        }
        return;
    }
    if (!m_globalShapeStale && m_globalShapeFor == glm::vec2(g, substepSeconds) && !m_globalShapeRows.empty())
        return;
    m_globalShapeFor = { g, substepSeconds };
    m_globalShapeStale = false;
    m_globalShapeRows.resize(m_restRows.size());
    const float exponent = substepSeconds / kGlobalShapeStepSeconds;
    m_pool->parallelFor(m_blocks.size(), 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            Block& b = m_blocks[i];
            GlobalShapeRow* rows = m_globalShapeRows.data() + (b.rest.data() - m_restRows.data());
            b.globalShape = std::span<const GlobalShapeRow>(rows, b.points);
            for (int l = 0; l < kLanes; ++l) {
                glm::vec3 p(b.shape[0].x[l], b.shape[0].y[l], b.shape[0].z[l]);
                float arc = 0.0f;
                for (std::uint32_t j = 0; j < b.points; ++j) {
                    if (j > 0) {
                        const ShapeRow& d = b.shape[j];
                        const float length = b.rest[j].length[l];
                        p += glm::vec3(d.x[l], d.y[l], d.z[l]) * length;
                        arc += length;
                    }
                    const float fade = std::max(0.0f, 1.0f - arc / (kGlobalShapeReach * b.strandLength[l]));
                    const float perStep = std::min(1.0f, g * fade);
                    rows[j].x[l] = p.x;
                    rows[j].y[l] = p.y;
                    rows[j].z[l] = p.z;
                    rows[j].share[l] = j == 0 ? 0.0f : 1.0f - std::pow(1.0f - perStep, exponent);
                }
            }
        }
    });
}

void Solver::step()
{
    StepConstants c;
    const SolverSettings& s = m_settings;
    c.substeps = s.substeps;
    c.dt = s.timeStepSeconds / static_cast<float>(s.substeps);
    c.keep = std::exp(-s.dampingPerSecond * c.dt);
    updateBendShares(c.dt);
    updateGlobalShape(c.dt);
    c.friction = s.friction;
    c.offset = s.hairOffsetMetres;
    c.velocityCorrection = s.velocityCorrection;
    c.drag = s.dragPerSecond;
    c.turbulence = s.turbulence;
    c.gravity = s.gravity;
    c.wind = s.wind;
    c.time = m_time;
    c.rotation = glm::mat3(m_headToWorld);
    c.translation = glm::vec3(m_headToWorld[3]);
    c.previousRotation = glm::mat3(m_previousHeadToWorld);
    c.previousTranslation = glm::vec3(m_previousHeadToWorld[3]);
    c.transformed = m_headToWorld != glm::mat4(1.0f) || m_previousHeadToWorld != glm::mat4(1.0f);
    c.field = m_field.get();
    for (const Capsule& cap : m_capsules)
        c.capsulesWorld.push_back(
            { c.rotation * cap.a + c.translation, c.rotation * cap.b + c.translation, cap.radiusMetres });
    c.resetCounter = &m_strandsReset;

    // Blocks are independent within a substep, so any split over threads gives the same bits.
    const bool globalShape = !m_globalShapeRows.empty();
    const bool volume = s.volume > 0.0f && !m_blocks.empty();
    auto advance = [&](int first, int end) {
        m_pool->parallelFor(m_blocks.size(), 4, [&](std::size_t begin, std::size_t stop) {
            HairVolumeGrid* const splatInto = volume && !m_volumeGrid->empty() ? m_volumeGrid.get() : nullptr;
            const int slot = splatInto ? splatInto->claimSlot() : 0;
            for (std::size_t i = begin; i < stop; ++i) {
                Block& b = m_blocks[i];
                auto run = [&](int from, int to) {
                    if (c.transformed)
                        globalShape ? advanceBlock<true, true>(b, c, from, to)
                                    : advanceBlock<true, false>(b, c, from, to);
                    else
                        globalShape ? advanceBlock<false, true>(b, c, from, to)
                                    : advanceBlock<false, false>(b, c, from, to);
                };
                if (!volume) {
                    run(first, end);
                    continue;
                }
                // The grid stays the same over [first, end): the block reads it before each of
                // these substeps and runs them in one go, in cache.
                for (int substep = first; substep < end; ++substep) {
                    volumeRead(b, c);
                    run(substep, substep + 1);
                }
                if (splatInto)
                    volumeSplat(b, c, slot); // for the next pass, while the block is in cache
            }
            if (splatInto)
                splatInto->releaseSlot(slot);
        });
    };
    if (volume) {
        // Hair-hair interaction needs every strand where it is when the grid is laid: the substeps
        // run outside the blocks, in runs after each of the volume grid's passes (its read is the
        // first thing each block does before each substep, in advance()).
        // The grid is laid again every kVolumeRefreshSeconds of substeps (every substep at the
        // default two substeps at 60 Hz; once a step for a heavy scene's many short substeps): in
        // that time hair moving at 0.5 m/s moves 4 mm, half a cell, so the field read at each
        // particle's own new position barely differs, while the pass is most of a substep's cost.
        // The push's stiffness is capped for the refresh interval, not the substep (volumePass).
        const int refreshEvery = volumeRefreshSubsteps(c.dt);
        if (m_headToWorld != m_volumeSplatHead) // the last splats are in the last step's head space
            m_volumeSplatted = false;
        for (int first = 0; first < c.substeps; first += refreshEvery) {
            const int end = std::min(first + refreshEvery, c.substeps);
            c.substep = first;
            volumePass(c, end - first);
            advance(first, end);
            m_volumeSplatted = true;
        }
        m_volumeSplatHead = m_headToWorld;
    } else {
        advance(0, c.substeps); // each block runs all its substeps in one go, in cache
        m_volumeSplatted = false;
    }
    m_previousHeadToWorld = m_headToWorld;
    m_time += s.timeStepSeconds;
}

void Solver::moveParticle(std::size_t strand, std::size_t point, const glm::vec3& position)
{
    if (strand >= m_slotOfStrand.size())
        return;
    const Slot slot = m_slotOfStrand[strand];
    Block& b = m_blocks[slot.block];
    if (point == 0 || point >= b.points)
        return;
    ParticleRow& row = b.state[point];
    m_volumeSplatted = false; // the grid's last splats are of the old state
    row.x[slot.lane] = row.px[slot.lane] = position.x;
    row.y[slot.lane] = row.py[slot.lane] = position.y;
    row.z[slot.lane] = row.pz[slot.lane] = position.z;
    row.clearance[slot.lane] = -1.0f;
}

std::string Solver::setStiffnessScales(std::span<const float> perStrand)
{
    if (perStrand.size() != m_strandCount)
        return "stiffness scales: " + std::to_string(perStrand.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    for (std::size_t i = 0; i < perStrand.size(); ++i)
        if (!(perStrand[i] >= 0.0f && perStrand[i] <= 1e3f))
            return "stiffness scale of strand " + std::to_string(i) + ": " + std::to_string(perStrand[i])
                + " is not a finite number of at least 0";
    for (std::size_t i = 0; i < perStrand.size(); ++i) {
        const Slot slot = m_slotOfStrand[i];
        m_blocks[slot.block].stiffnessScale[slot.lane] = perStrand[i];
    }
    for (Block& b : m_blocks) // padding lanes copy their block's first strand
        for (int l = 0; l < kLanes; ++l)
            if (b.strand[l] < 0)
                b.stiffnessScale[l] = b.stiffnessScale[0];
    m_bendSharesStale = true;
    return {};
}

std::string Solver::setStrandAir(std::span<const float> dragScale, std::span<const glm::vec3> extraWind)
{
    if (!dragScale.empty() && dragScale.size() != m_strandCount)
        return "drag scales: " + std::to_string(dragScale.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    if (!extraWind.empty() && extraWind.size() != m_strandCount)
        return "strand winds: " + std::to_string(extraWind.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    for (std::size_t i = 0; i < dragScale.size(); ++i)
        if (!(dragScale[i] >= 0.0f && dragScale[i] <= 1e3f))
            return "drag scale of strand " + std::to_string(i) + ": " + std::to_string(dragScale[i])
                + " is not a finite number of at least 0";
    for (std::size_t i = 0; i < extraWind.size(); ++i)
        if (!(std::abs(extraWind[i].x) <= 1e3f && std::abs(extraWind[i].y) <= 1e3f && std::abs(extraWind[i].z) <= 1e3f))
            return "wind of strand " + std::to_string(i) + " is not a finite speed below 1000 m/s";
    for (std::size_t i = 0; i < m_strandCount; ++i) {
        const Slot slot = m_slotOfStrand[i];
        Block& b = m_blocks[slot.block];
        b.dragScale[slot.lane] = dragScale.empty() ? 1.0f : dragScale[i];
        const glm::vec3 w = extraWind.empty() ? glm::vec3(0.0f) : extraWind[i];
        b.windX[slot.lane] = w.x;
        b.windY[slot.lane] = w.y;
        b.windZ[slot.lane] = w.z;
    }
    return {};
}

void Solver::copyState(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& previous) const
{
    copyPositions(positions);
    previous.resize(positions.size());
    for (std::size_t strand = 0; strand < m_strandCount; ++strand) {
        const Slot slot = m_slotOfStrand[strand];
        const Block& b = m_blocks[slot.block];
        for (std::uint32_t j = 0; j < b.points; ++j) {
            const ParticleRow& row = b.state[j];
            previous[m_restOffsets[strand] + j] = { row.px[slot.lane], row.py[slot.lane], row.pz[slot.lane] };
        }
    }
}

bool Solver::setStrandState(
    std::size_t strand, std::span<const glm::vec3> positions, std::span<const glm::vec3> previous)
{
    if (strand >= m_strandCount)
        return false;
    const Slot slot = m_slotOfStrand[strand];
    Block& b = m_blocks[slot.block];
    if (positions.size() != b.points || previous.size() != b.points)
        return false;
    m_volumeSplatted = false; // the grid's last splats are of the old state
    for (std::uint32_t j = 0; j < b.points; ++j)
        if (!std::isfinite(
                positions[j].x + positions[j].y + positions[j].z + previous[j].x + previous[j].y + previous[j].z))
            return false;
    for (std::uint32_t j = 1; j < b.points; ++j) { // the root stays where its rest shape pins it
        ParticleRow& row = b.state[j];
        row.x[slot.lane] = positions[j].x;
        row.y[slot.lane] = positions[j].y;
        row.z[slot.lane] = positions[j].z;
        row.px[slot.lane] = previous[j].x;
        row.py[slot.lane] = previous[j].y;
        row.pz[slot.lane] = previous[j].z;
        row.clearance[slot.lane] = -1.0f;
    }
    return true;
}

bool Solver::setStrandRestDirections(std::size_t strand, std::span<const glm::vec3> restShape)
{
    if (strand >= m_strandCount)
        return false;
    const Slot slot = m_slotOfStrand[strand];
    Block& b = m_blocks[slot.block];
    if (restShape.size() != b.points)
        return false;
    const int l = static_cast<int>(slot.lane);
    if (glm::distance(restShape[0], glm::vec3(b.shape[0].x[l], b.shape[0].y[l], b.shape[0].z[l])) > 1e-6f)
        return false;
    for (std::uint32_t j = 1; j < b.points; ++j) {
        const float length = glm::distance(restShape[j], restShape[j - 1]);
        if (!(std::abs(length - b.rest[j].length[l]) <= 1e-3f * b.rest[j].length[l]))
            return false;
    }
    for (std::uint32_t j = 1; j < b.points; ++j) {
        const glm::vec3 d = glm::normalize(restShape[j] - restShape[j - 1]);
        b.shape[j].x[l] = d.x;
        b.shape[j].y[l] = d.y;
        b.shape[j].z[l] = d.z;
    }
    storeRestFrames(b, l);
    m_globalShapeStale = true;
    return true;
}

void Solver::copyPositions(std::vector<glm::vec3>& out) const
{
    out.resize(m_restOffsets.empty() ? 0 : m_restOffsets.back());
    m_pool->parallelFor(m_blocks.size(), 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const Block& b = m_blocks[i];
            for (int l = 0; l < kLanes; ++l) {
                if (b.strand[l] < 0)
                    continue;
                glm::vec3* dst = out.data() + m_restOffsets[static_cast<std::size_t>(b.strand[l])];
                for (std::uint32_t j = 0; j < b.points; ++j)
                    dst[j] = { b.state[j].x[l], b.state[j].y[l], b.state[j].z[l] };
            }
        }
    });
}

std::size_t Solver::memoryBytes() const
{
    return m_restOffsets.capacity() * sizeof(std::uint32_t) + m_blocks.capacity() * sizeof(Block)
        + m_slotOfStrand.capacity() * sizeof(Slot) + m_stateRows.capacity() * sizeof(ParticleRow)
        + m_restRows.capacity() * sizeof(RestRow) + m_shapeRows.capacity() * sizeof(ShapeRow)
        + m_globalShapeRows.capacity() * sizeof(GlobalShapeRow) + (m_volumeGrid ? m_volumeGrid->memoryBytes() : 0);
}

} // namespace wisp
