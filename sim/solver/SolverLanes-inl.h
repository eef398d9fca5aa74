// The few operations the solver's kernels need on its lanes (SolverLanes.h), as single
// instructions where the CPU has them, for the SIMD target being compiled: included once per
// target by a file that dispatches at run time (Google Highway's foreach_target.h: the kernels are
// compiled for SSE4, AVX2 and AVX-512 and the best the CPU has runs), or once for the build's own
// target by any other. Everything is in wisp::HWY_NAMESPACE::lanes. Internal to sim/solver.

// Per-target include guard (Highway's convention): included again for each target.
#if defined(WISP_SOLVER_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WISP_SOLVER_LANES_INL_H_
#undef WISP_SOLVER_LANES_INL_H_
#else
#define WISP_SOLVER_LANES_INL_H_
#endif

#include "sim/solver/SolverLanes.h"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <hwy/highway.h>

#include <cstdint>
#include <cstring>
#if HWY_ARCH_X86
#include <immintrin.h>
#endif

// Which intrinsics this target has (GCC does not define __AVX512F__ and the like inside Highway's
// per-target regions: HWY_TARGET says it).
#undef WISP_LANES_AVX512
#undef WISP_LANES_AVX
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
#define WISP_LANES_AVX512 1
#define WISP_LANES_AVX 1
#elif HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
#define WISP_LANES_AVX512 0
#define WISP_LANES_AVX 1
#else
#define WISP_LANES_AVX512 0
#define WISP_LANES_AVX 0
#endif

HWY_BEFORE_NAMESPACE();
namespace wisp::HWY_NAMESPACE {

namespace lanes {

// (Internal linkage: each kernel file inlines these as it sees fit.)
namespace {

// The kernel's own vector (SolverBlockKernel.cpp): as many floats as one register of this target
// holds (16 on AVX-512, 8 on AVX2, 4 on SSE4 and NEON). A block's 16 lanes are run a slice of
// kVectorLanes at a time, so no value spans two registers (a 16-lane vector on AVX2 is two, and
// the kernel's many live values spilled). Everything else (the volume grid's rows, which shuffle
// across all 16 lanes) keeps Lane.
#if WISP_LANES_AVX512
constexpr int kVectorLanes = 16;
using Vec = Lane;
using VecMask = Mask;
#else
constexpr int kVectorLanes = WISP_LANES_AVX ? 8 : 4;
using Vec = float __attribute__((vector_size(kVectorLanes * sizeof(float)), aligned(kVectorLanes * sizeof(float))));
using VecMask = int __attribute__((vector_size(kVectorLanes * sizeof(int)), aligned(kVectorLanes * sizeof(int))));
#endif
static_assert(kLanes % kVectorLanes == 0, "a block's lanes are whole slices");

// The integer vector of a float vector's comparisons.
template <class L> using MaskOf = decltype(L{} < L{});

inline Lane splat(float v)
{
    return Lane{} + v;
}
template <class L> inline L splatAs(float v)
{
    return L{} + v;
}
template <class M, class L> inline L select(M m, L a, L b)
{
    return m ? a : b;
}

// min, max, |a| and "any lane set" as single instructions per register. GCC lowers the portable
// forms (a < b ? a : b, a reduction loop) to compare-and-blend, or, for a 16-lane vector on an
// AVX2 machine, to scalar code lane by lane. minps/maxps return their second operand when the
// first comparison fails (NaN included), exactly as a < b ? a : b does, so results are unchanged.
template <class L> inline L lmin(L a, L b)
{
    return a < b ? a : b;
}
template <class L> inline L lmax(L a, L b)
{
    return a > b ? a : b;
}
template <class M> inline bool anyOf(M m)
{
    int any = 0;
    for (int i = 0; i < static_cast<int>(sizeof(M) / sizeof(int)); ++i)
        any |= m[i];
    return any != 0;
}
#if WISP_LANES_AVX512
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
#elif WISP_LANES_AVX
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
static_assert(sizeof(Vec) == sizeof(__m256));
inline Vec lmin(Vec a, Vec b)
{
    return reinterpret_cast<Vec>(_mm256_min_ps(reinterpret_cast<__m256>(a), reinterpret_cast<__m256>(b)));
}
inline Vec lmax(Vec a, Vec b)
{
    return reinterpret_cast<Vec>(_mm256_max_ps(reinterpret_cast<__m256>(a), reinterpret_cast<__m256>(b)));
}
inline bool anyOf(VecMask m)
{
    const __m256 v = reinterpret_cast<__m256>(m);
    return !_mm256_testz_ps(v, v);
}
#elif HWY_ARCH_X86
static_assert(sizeof(Vec) == sizeof(__m128));
inline Vec lmin(Vec a, Vec b)
{
    return reinterpret_cast<Vec>(_mm_min_ps(reinterpret_cast<__m128>(a), reinterpret_cast<__m128>(b)));
}
inline Vec lmax(Vec a, Vec b)
{
    return reinterpret_cast<Vec>(_mm_max_ps(reinterpret_cast<__m128>(a), reinterpret_cast<__m128>(b)));
}
inline bool anyOf(VecMask m)
{
    return _mm_movemask_ps(reinterpret_cast<__m128>(m)) != 0;
}
#endif
template <class L> inline L lsqrt(L a)
{
    L r;
    for (int i = 0; i < static_cast<int>(sizeof(L) / sizeof(float)); ++i)
        r[i] = __builtin_sqrtf(a[i]);
    return r;
}
// 1/sqrt(a) and 1/a, exactly (IEEE square root and division, the same bits on every target). The
// hardware estimates refined by a Newton step were a little quicker on the strand's serial chain
// (groom-1m 3 %), but they differ between AVX-512 (14-bit tables), AVX (12-bit) and SSE4 (none), and
// between CPU makers, and a default scene's 240 steps took those last bits to 0.26 mm (AVX2 against
// AVX-512) and 14 mm (SSE4): with these, and no contraction into FMA (-ffp-contract=off,
// CMakeLists.txt), every target gives the same bits (SimdTargetTest.cpp).
template <class L> inline L lrsqrt(L a)
{
    return splatAs<L>(1.0f) / lsqrt(a);
}
template <class L> inline L lrcp(L a)
{
    return splatAs<L>(1.0f) / a;
}

// (A vector type's aligned attribute does not pass through a template argument, GCC says so: the
// members are aligned to their size here instead.)
//
// Copied member by member, by the constructor and assignment below, not as the 96-byte aggregate
// (on AVX2) that GCC 12 copies in pieces: where a copy lived on the stack it stored the registers
// and read them back eight bytes at a time into 16-byte halves (`vmovq`, `vpinsrq`), a stall on
// every copy of a particle's position in the block kernel. Callgrind, AVX2, one thread, 50 steps:
// the limp kernel's instructions on the small sphere 93.6 M -> 83.7 M, the bending kernel's on
// paper-25x25x20 without volume 72.4 M -> 66.9 M; the same bits (docs/performance-log.md, "The
// three-lane vector copied member by member").
template <class L> struct V3T {
    alignas(sizeof(L)) L x;
    alignas(sizeof(L)) L y;
    alignas(sizeof(L)) L z;
    V3T() = default; // (V3T{} is zeros, as for the aggregate: value-initialised)
    V3T(L x_, L y_, L z_)
        : x(x_)
        , y(y_)
        , z(z_)
    {
    }
    V3T(const V3T& o)
        : x(o.x)
        , y(o.y)
        , z(o.z)
    {
    }
    V3T& operator=(const V3T& o)
    {
        x = o.x;
        y = o.y;
        z = o.z;
        return *this;
    }
};
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes"
using V3 = V3T<Lane>;
#pragma GCC diagnostic pop
template <class L> inline V3T<L> operator+(const V3T<L>& a, const V3T<L>& b)
{
    return { a.x + b.x, a.y + b.y, a.z + b.z };
}
template <class L> inline V3T<L> operator-(const V3T<L>& a, const V3T<L>& b)
{
    return { a.x - b.x, a.y - b.y, a.z - b.z };
}
template <class L> inline V3T<L> operator*(const V3T<L>& a, L s)
{
    return { a.x * s, a.y * s, a.z * s };
}
template <class L> inline L dot(const V3T<L>& a, const V3T<L>& b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
// |a| by clearing the sign bit (one and; -0 becomes +0, which no comparison tells apart).
template <class L> inline L labs(L a)
{
    return reinterpret_cast<L>(reinterpret_cast<MaskOf<L>>(a) & 0x7fffffff);
}
template <class L> inline L l1Length(const V3T<L>& a)
{
    return labs(a.x) + labs(a.y) + labs(a.z);
}
template <class L> inline V3T<L> cross(const V3T<L>& a, const V3T<L>& b)
{
    return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
template <class M, class L> inline V3T<L> select(M m, const V3T<L>& a, const V3T<L>& b)
{
    return { m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z };
}
inline V3 splat(const glm::vec3& v)
{
    return { splat(v.x), splat(v.y), splat(v.z) };
}
template <class L> inline V3T<L> splatAs(const glm::vec3& v)
{
    return { splatAs<L>(v.x), splatAs<L>(v.y), splatAs<L>(v.z) };
}
template <class L> inline V3T<L> transform(const glm::mat3& m, const V3T<L>& v) // m * v, glm is column-major
{
    return { v.x * m[0][0] + v.y * m[1][0] + v.z * m[2][0], v.x * m[0][1] + v.y * m[1][1] + v.z * m[2][1],
        v.x * m[0][2] + v.y * m[1][2] + v.z * m[2][2] };
}

// sin(x) for the gusts: x reduced to [-pi, pi], then an odd polynomial (Taylor to x^11, error
// below 1e-3). Vectorised so that turbulence costs a few instructions per strand, not six libm calls.
template <class L> inline L lsin(L x)
{
    constexpr float kInvTwoPi = 0.15915494f, kTwoPi = 6.2831853f;
    const L turns = x * kInvTwoPi;
    const L rounded = (turns + 12582912.0f) - 12582912.0f; // round to nearest (|turns| < 2^22)
    const L r = x - rounded * kTwoPi;
    const L r2 = r * r;
    return r
        * (1.0f
            + r2
                * (-1.0f / 6
                    + r2 * (1.0f / 120 + r2 * (-1.0f / 5040 + r2 * (1.0f / 362880 + r2 * (-1.0f / 39916800))))));
}

// Floats to 64-bit integers, truncated toward zero, as C++'s conversion gives them for |v| < 2^63 (the
// volume grid's fixed point keeps its values below 2^61), and beyond that, NaN included, INT64_MIN
// on every x86 target, as x86's own conversions give it; four or eight at a time: the volume
// grid's splats (HairVolumeGrid.cpp, HairVolumeGridNearest-inl.h). GCC 12 converts a vector of
// them lane by lane below AVX-512, which has the instruction: a scalar conversion and two moves
// a lane, most of an AVX2 trilinear splat's flush (perf, paper-35x35x30). On AVX2 the float's
// fields do it: the mantissa with its hidden bit, shifted by the exponent (the variable 64-bit
// shifts give 0 for a count past 63, so one of the two shifts is always a no-op), then the sign.
using Float4 = float __attribute__((vector_size(4 * sizeof(float))));
using Float8 = float __attribute__((vector_size(8 * sizeof(float))));
using Int64x4 = std::int64_t __attribute__((vector_size(4 * sizeof(std::int64_t))));
using Int64x8 = std::int64_t __attribute__((vector_size(8 * sizeof(std::int64_t))));
inline Int64x4 truncateToInt64(Float4 v)
{
#if WISP_LANES_AVX512
    __m128 in;
    std::memcpy(&in, &v, sizeof in);
    const __m256i out = _mm256_cvttps_epi64(in);
#elif WISP_LANES_AVX
    __m128i in;
    std::memcpy(&in, &v, sizeof in);
    const __m256i bits = _mm256_cvtepu32_epi64(in); // each float's bits in a 64-bit lane
    const __m256i exponent = _mm256_and_si256(_mm256_srli_epi64(bits, 23), _mm256_set1_epi64x(0xFF));
    const __m256i mantissa
        = _mm256_or_si256(_mm256_and_si256(bits, _mm256_set1_epi64x(0x7FFFFF)), _mm256_set1_epi64x(0x800000));
    // |v| = mantissa x 2^(exponent - 150): left by the difference, or right by its opposite.
    const __m256i left = _mm256_sub_epi64(exponent, _mm256_set1_epi64x(150));
    const __m256i right = _mm256_sub_epi64(_mm256_set1_epi64x(150), exponent);
    const __m256i magnitude = _mm256_or_si256(_mm256_sllv_epi64(mantissa, left), _mm256_srlv_epi64(mantissa, right));
    const __m256i sign = _mm256_sub_epi64(_mm256_setzero_si256(), _mm256_srli_epi64(bits, 31)); // 0 or -1
    const __m256i truncated = _mm256_sub_epi64(_mm256_xor_si256(magnitude, sign), sign);
    // Beyond (NaN, infinities, |v| >= 2^63): x86's "integer indefinite", as the AVX-512 and the
    // scalar conversions give it, so that every target gives the same bits for any input.
    const __m256i beyond = _mm256_cmpgt_epi64(exponent, _mm256_set1_epi64x(126 + 63));
    const __m256i out = _mm256_blendv_epi8(truncated, _mm256_set1_epi64x(INT64_MIN), beyond);
#else
    const Int64x4 out = __builtin_convertvector(v, Int64x4);
#endif
    Int64x4 result;
    std::memcpy(&result, &out, sizeof result);
    return result;
}
inline Int64x8 truncateToInt64(Float8 v)
{
#if WISP_LANES_AVX512
    __m256 in;
    std::memcpy(&in, &v, sizeof in);
    const __m512i out = _mm512_cvttps_epi64(in);
    Int64x8 result;
    std::memcpy(&result, &out, sizeof result);
    return result;
#else
    const Float4 low = { v[0], v[1], v[2], v[3] }, high = { v[4], v[5], v[6], v[7] };
    const Int64x4 lo = truncateToInt64(low), hi = truncateToInt64(high);
    return Int64x8{ lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3] };
#endif
}

// Rounded half away from zero, then truncated: the volume grid's fixed point (both splats), so that
// its sums do not drift toward zero.
template <class F> inline auto roundToInt64(F v)
{
    return truncateToInt64(v + (v < 0.0f ? F{} - 0.5f : F{} + 0.5f));
}

} // namespace

} // namespace lanes

// The names the block kernel and its pure lane functions (SolverConstraints.h, SolverContact.h)
// use: the same as lanes', for the kernel's vector, one register wide (lanes::Vec).
namespace kernel {
namespace {
using Lane = lanes::Vec;
using Mask = lanes::VecMask;
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes"
using V3 = lanes::V3T<Lane>;
#pragma GCC diagnostic pop
constexpr int kVecLanes = lanes::kVectorLanes;
inline Lane splat(float v)
{
    return Lane{} + v;
}
inline V3 splat(const glm::vec3& v)
{
    return { splat(v.x), splat(v.y), splat(v.z) };
}
using lanes::anyOf;
using lanes::cross;
using lanes::dot;
using lanes::l1Length;
using lanes::labs;
using lanes::lmax;
using lanes::lmin;
using lanes::lrcp;
using lanes::lrsqrt;
using lanes::lsin;
using lanes::lsqrt;
using lanes::select;
using lanes::transform;
using lanes::operator+;
using lanes::operator-;
using lanes::operator*;
} // namespace
} // namespace kernel

} // namespace wisp::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif // per-target include guard
