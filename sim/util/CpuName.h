#pragma once
// The CPU this process runs on, by the name its maker gives it, for the figures a benchmark prints
// and the About box (a speed figure means little without the machine it was measured on; the SIMD
// targets it can run are SimdTarget.h's).

#include <string>

namespace wisp {

// "Intel(R) Xeon(R) Processor @ 2.80GHz", "AMD EPYC 7B13", ...: on x86 the CPUID brand string, on
// other CPUs /proc/cpuinfo's model name; "unknown CPU" where neither says. Spaces collapsed.
std::string cpuModelName();

} // namespace wisp
