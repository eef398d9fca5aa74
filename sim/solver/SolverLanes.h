#pragma once
// The solver's lanes: 16 floats, the same particle of 16 strands (Solver.h). The types only; the
// operations the kernels need on them are compiled once for each SIMD target the binary carries
// (SolverLanes-inl.h).

namespace wisp {

// A lane: 16 floats (GCC/Clang vector extension: one AVX-512 register, two AVX or four SSE/NEON ones).
constexpr int kLanes = 16;
// Aligned to their size on every target: GCC otherwise gives a 64-byte vector the alignment of the
// widest register the compiling target has (16 bytes on the x86-64-v2 baseline), so blocks allocated
// by baseline code would not be aligned for the AVX-512 kernel's aligned loads.
using Lane = float __attribute__((vector_size(kLanes * sizeof(float)), aligned(kLanes * sizeof(float))));
using Mask = int __attribute__((vector_size(kLanes * sizeof(int)), aligned(kLanes * sizeof(int))));

} // namespace wisp
