#pragma once
// The SIMD instruction set this build's solver was compiled for, by name, so `wisp-cli bench`
// can say what it measured (the solver's lanes are 16 floats: one register with AVX-512, two
// with AVX2, four with SSE or NEON; sim/solver/SolverLanes.h).
// Thread: any.

namespace wisp {

// "AVX-512", "AVX2", "AVX", "SSE4", "SSE2", "NEON" or "scalar": the widest set the compiler was
// allowed to use (-march; see WISP_NATIVE in CMakeLists.txt).
constexpr const char* compiledSimdTarget()
{
#if defined(__AVX512F__)
    return "AVX-512";
#elif defined(__AVX2__)
    return "AVX2";
#elif defined(__AVX__)
    return "AVX";
#elif defined(__SSE4_1__)
    return "SSE4";
#elif defined(__SSE2__)
    return "SSE2";
#elif defined(__ARM_NEON)
    return "NEON";
#else
    return "scalar";
#endif
}

// Floats one vector register holds for the compiled target.
constexpr int compiledVectorFloats()
{
#if defined(__AVX512F__)
    return 16;
#elif defined(__AVX__)
    return 8;
#elif defined(__SSE2__) || defined(__ARM_NEON)
    return 4;
#else
    return 1;
#endif
}

} // namespace wisp
