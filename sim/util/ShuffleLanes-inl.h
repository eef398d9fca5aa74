// r[i] = v[Index[i]] for GCC/Clang vector-extension vectors and an index table known at compile
// time (indices taken modulo the lane count): a permute or two on any target. (A run-time index
// vector, GCC's __builtin_shuffle, went lane by lane through memory for a 16-lane vector on AVX2,
// and Clang, the fuzz build, lacks it.)
// Compiled once per SIMD target, as sim/solver/SolverLanes-inl.h: a 64-byte vector passed to a
// function compiled for another target changes the call's ABI (Clang refuses it).

#if defined(WISP_SHUFFLE_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WISP_SHUFFLE_LANES_INL_H_
#undef WISP_SHUFFLE_LANES_INL_H_
#else
#define WISP_SHUFFLE_LANES_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>
#include <utility>

HWY_BEFORE_NAMESPACE();
namespace wisp::HWY_NAMESPACE {

// The table: a constexpr std::array<int, lanes> with static storage.
template <const auto& Index, class Vector> inline Vector shuffleLanesBy(Vector v)
{
    constexpr int lanes = static_cast<int>(sizeof(Vector) / sizeof(v[0]));
    static_assert(static_cast<int>(Index.size()) == lanes);
    return [&]<std::size_t... I>(std::index_sequence<I...>)
    {
        return __builtin_shufflevector(v, v, (Index[I] & (lanes - 1))...);
    }
    (std::make_index_sequence<lanes>{});
}

} // namespace wisp::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif // per-target include guard
