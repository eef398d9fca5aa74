#pragma once
// A cache hint for the solver's loops. Internal to sim/solver.

namespace wisp {

// Asks for the 64-byte line at `at` (a hint only: nothing is read, and an address outside any
// object is harmless), in inline assembly on x86: GCC 12 dropped some of the block kernel's
// __builtin_prefetch calls from the binary (the next block's shape rows; and its rows' prefetches
// once they were split between slices: the AVX-512 bending kernel's 29 prefetch instructions became
// 16, and groom-1m was 30 % slower).
inline void prefetchLine(const void* at)
{
#if defined(__x86_64__) || defined(__i386__)
    asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(at)));
#else // (x86's instruction would not assemble for ARM, where GCC was not seen to drop the hint)
    __builtin_prefetch(at);
#endif
}

} // namespace wisp
