#pragma once
// The SIMD instruction sets the solver runs on. Its kernels (sim/solver/*-inl.h users) are compiled
// once per target (Google Highway's dynamic dispatch: SSE4, AVX2 and AVX-512 on x86; NEON and SVE
// where built for ARM), and each call runs the best target this CPU has, unless one is forced
// (forceSimdTarget, `wisp-cli bench --target`). Names as the README and `wisp-cli bench` print them:
// "AVX-512", "AVX2", "SSE4", "NEON", "SVE", "SVE2", "EMU128" or "scalar".
// Thread: solverSimdTarget() and solverVectorFloats() any; availableSimdTargets() and
// forceSimdTarget() only while no solver is stepping (they set Highway's target mask, which a
// dispatch reads).

#include <string>
#include <vector>

namespace wisp {

// The target the solver's kernels run on now.
const char* solverSimdTarget();
// Floats one of its vector registers holds (the solver's lanes are 16 floats: one AVX-512
// register, two AVX2, four SSE4 or NEON ones).
int solverVectorFloats();
// Every target compiled into this binary that this CPU can run, best first.
std::vector<std::string> availableSimdTargets();
// Runs the kernels on `name` (one of availableSimdTargets(), case-insensitive; "AVX3" and "AVX512"
// name AVX-512 too) until the next call; empty: the best again. Returns an empty string, or why not.
std::string forceSimdTarget(const std::string& name);

// The widest instruction set the rest of the build may use (its -march baseline, WISP_MARCH and
// WISP_NATIVE in CMakeLists.txt): "AVX-512", "AVX2", "AVX", "SSE4", "SSE2", "NEON" or "scalar".
constexpr const char* baselineSimdTarget()
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

} // namespace wisp
