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
// 1/sqrt(a) and 1/a, exactly (IEEE square root and division, the same bits on every target). The
// hardware estimates refined by a Newton step were a little quicker on the strand's serial chain
// (groom-1m 3 %), but they differ between AVX-512 (14-bit tables), AVX (12-bit) and SSE4 (none), and
// between CPU makers, and a default scene's 240 steps took those last bits to 0.26 mm (AVX2 against
// AVX-512) and 14 mm (SSE4): with these, and no contraction into FMA (-ffp-contract=off,
// CMakeLists.txt), every target gives the same bits (SimdTargetTest.cpp).
inline Lane lrsqrt(Lane a)
{
    return splat(1.0f) / lsqrt(a);
}
inline Lane lrcp(Lane a)
{
    return splat(1.0f) / a;
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

} // namespace

} // namespace lanes

} // namespace wisp::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif // per-target include guard
