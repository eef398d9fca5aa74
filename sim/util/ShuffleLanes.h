#pragma once
// r[i] = v[index[i]] for GCC/Clang vector-extension vectors (indices taken modulo the lane count):
// GCC's __builtin_shuffle, which Clang (the fuzz build, scripts/fuzz.sh) lacks for a run-time
// index vector, so Clang gets the same result lane by lane.

namespace wisp {

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

} // namespace wisp
