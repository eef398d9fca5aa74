// The lanes' float-to-64-bit conversion (lanes::truncateToInt64, SolverLanes-inl.h), which the
// volume grid's fixed point rests on: one instruction on AVX-512, the float's own fields on AVX2,
// the compiler's lane-by-lane conversion on SSE4. On every target this CPU runs it must give what
// C++'s conversion gives (truncation toward zero) for every float below 2^63 in magnitude: zeros,
// subnormals, fractions, the halves the fixed point's rounding adds, every exponent up to 62 with
// mantissas across their range, both signs; and beyond (NaN, infinities), INT64_MIN on x86, as
// x86's own conversions give it. Compiled once per target, as the solver's kernels are.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "tests/sim/LaneConversionTest.cpp"
#include <hwy/foreach_target.h> // (before highway.h)

#include "sim/solver/SolverLanes-inl.h"

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>
#include <cstring>

HWY_BEFORE_NAMESPACE();
namespace wisp::HWY_NAMESPACE {

// `count` floats (a multiple of 8) to integers: the first half of each eight through the
// four-lane overload, the second through the eight-lane one.
void truncateOnTarget(const float* in, std::int64_t* out, std::size_t count)
{
    for (std::size_t i = 0; i + 8 <= count; i += 8) {
        lanes::Float4 four;
        std::memcpy(&four, in + i, sizeof four);
        const lanes::Int64x4 fourOut = lanes::truncateToInt64(four);
        std::memcpy(out + i, &fourOut, sizeof fourOut);
        lanes::Float8 eight;
        std::memcpy(&eight, in + i, sizeof eight);
        const lanes::Int64x8 eightOut = lanes::truncateToInt64(eight);
        // Lanes 4..7 from the eight-lane conversion; lanes 0..3 of it must agree with the four's.
        for (int l = 0; l < 4; ++l) {
            out[i + 4 + static_cast<std::size_t>(l)] = eightOut[l + 4];
            if (eightOut[l] != fourOut[l])
                out[i + static_cast<std::size_t>(l)] = 0x5a5a5a5a5a5a5a5a; // (no conversion gives this)
        }
    }
}

} // namespace wisp::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

#include "sim/util/SimdTarget.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace wisp {

HWY_EXPORT(truncateOnTarget);

namespace {

std::vector<float> valuesToConvert()
{
    std::vector<float> v = { 0.0f, -0.0f, 0.5f, -0.5f, 0.49999997f, 0.99999994f, -0.99999994f, 1.0f, -1.0f, 1.5f, -1.5f,
        2.5f, -2.5f, 8388607.5f, -8388607.5f, 8388608.0f, 16777215.0f, 16777216.0f, -16777216.0f, 2147483520.0f,
        -2147483648.0f, 2147483648.0f, 4294967296.0f, -4294967296.0f,
        std::bit_cast<float>(0x00000001u), // the least subnormal
        std::bit_cast<float>(0x807FFFFFu), // the largest negative subnormal
        std::bit_cast<float>(0x5EFFFFFFu), // the largest float below 2^63
        std::bit_cast<float>(0xDEFFFFFFu), std::ldexp(1.0f, 61), -std::ldexp(1.0f, 62) };
    // Every exponent from 2^-3 to 2^62, mantissas from a fixed sequence, both signs.
    std::uint32_t state = 12345u;
    for (int exponent = -3; exponent <= 62; ++exponent)
        for (int k = 0; k < 64; ++k) {
            state = state * 1664525u + 1013904223u;
            const float mantissa = 1.0f + static_cast<float>(state >> 9) * 0x1p-23f; // [1, 2)
            const float value = std::ldexp(mantissa, exponent);
            v.push_back(k % 2 ? -value : value);
        }
#if defined(__x86_64__) || defined(__i386__)
    // Beyond C++'s range: x86's "integer indefinite" (INT64_MIN) on every x86 target (ARM's own
    // conversion saturates instead, and NaN gives 0 there).
    for (const float beyond : { std::ldexp(1.0f, 63), -std::ldexp(1.0f, 63), 1e30f, -1e38f,
             std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
             std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN() })
        v.push_back(beyond);
#endif
    while (v.size() % 8 != 0)
        v.push_back(3.0f);
    return v;
}

struct ForcedTarget {
    explicit ForcedTarget(const std::string& name) { error = forceSimdTarget(name); }
    ~ForcedTarget() { forceSimdTarget(""); }
    std::string error;
};

TEST(LaneConversion, EveryTargetTruncatesFloatsToInt64AsCppDoes)
{
    const std::vector<float> in = valuesToConvert();
    for (const std::string& target : availableSimdTargets()) {
        ForcedTarget forced(target);
        ASSERT_EQ(forced.error, "");
        std::vector<std::int64_t> out(in.size(), -7);
        HWY_DYNAMIC_DISPATCH(truncateOnTarget)(in.data(), out.data(), in.size());
        int wrong = 0;
        for (std::size_t i = 0; i < in.size(); ++i) {
            const std::int64_t expected = std::abs(in[i]) < 0x1p63f ? static_cast<std::int64_t>(in[i])
                                                                    : std::numeric_limits<std::int64_t>::min();
            if (out[i] != expected && ++wrong <= 5)
                ADD_FAILURE() << target << ": " << in[i] << " (bits 0x" << std::hex
                              << std::bit_cast<std::uint32_t>(in[i]) << std::dec << ") gave " << out[i] << ", expected "
                              << expected;
        }
        EXPECT_EQ(wrong, 0) << target;
    }
}

} // namespace
} // namespace wisp

#endif // HWY_ONCE
