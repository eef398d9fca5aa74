#pragma once
// The solver's lanes: 16 floats that one instruction (or a few) handles, the same particle of 16
// strands (Solver.h), and the few operations the kernels need on them, as single instructions
// where the CPU has them. Internal to sim/solver (Solver*.cpp).

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace wisp {

// A lane: 16 floats (GCC/Clang vector extension: one AVX-512 register, or two AVX halves).
constexpr int kLanes = 16;
using Lane = float __attribute__((vector_size(kLanes * sizeof(float))));
using Mask = int __attribute__((vector_size(kLanes * sizeof(int))));

namespace lanes {

// (Internal linkage, as when this lived in one file: each kernel file inlines these as it sees fit.)
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

} // namespace wisp
