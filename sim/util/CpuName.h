#pragma once
// The CPU this process runs on, by the name its maker gives it, for the figures a benchmark prints
// and the About box (a speed figure means little without the machine it was measured on; the SIMD
// targets it can run are SimdTarget.h's).

#include <string>

namespace wisp {

// "Intel(R) Xeon(R) Processor @ 2.80GHz", "AMD EPYC 7B13", ...: on x86 the CPUID brand string, on
// other CPUs /proc/cpuinfo's name for it (cpuModelFromCpuinfo); "unknown CPU" where neither says.
// Spaces collapsed. (An ARM Linux often names only the board, a Raspberry Pi's "Model", or nothing.)
std::string cpuModelName();

// The CPU's name in a /proc/cpuinfo text: the first non-empty "model name" (x86, some ARM),
// "cpu model" (MIPS), "Model" or "Hardware" (ARM boards) line's value, spaces collapsed; empty
// where there is none.
std::string cpuModelFromCpuinfo(const std::string& cpuinfo);

// `text` with its runs of spaces and tabs made one space, none at the ends, up to its first NUL
// (a CPUID brand string is padded with both).
std::string collapsedSpaces(const std::string& text);

} // namespace wisp
