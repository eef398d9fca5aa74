// r[i] = v[index[i]] for GCC/Clang vector-extension vectors (indices taken modulo the lane count):
// GCC's __builtin_shuffle, which Clang (the fuzz build, scripts/fuzz.sh) lacks for a run-time
// index vector, so Clang gets the same result lane by lane.
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

template <class Vector, class IndexVector> inline Vector shuffleLanes(Vector v, IndexVector index)
{
#if defined(__clang__)
    constexpr int lanes = static_cast<int>(sizeof(Vector) / sizeof(v[0]));
    Vector r;
    for (int i = 0; i < lanes; ++i)
        r[i] = v[index[i] & (lanes - 1)];
    return r;
#else
    return __builtin_shuffle(v, index);
#endif
}

// The same for an index table known at compile time (a constexpr std::array<int, lanes> with static
// storage): a permute or two on any target, where a run-time index on a vector of two registers
// (16 lanes on AVX2) goes lane by lane through memory.
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
