#pragma once
// How the process's heap hands freed memory back, set once at start (the editor's main, the GUI
// tests' main: they measure what the editor does).
//
// Why: Mesa's software rasteriser (llvmpipe) allocates its vertex and scene memory afresh for every
// paint, tens of megabytes of small blocks, and frees it after. glibc returns the freed top of the
// heap to the kernel once more than 128 KiB of it is free, so the next paint grew the heap again and
// took a page fault for every 4 KiB of it: on this project's 2-vCPU machine about a tenth of a
// paused orbit's CPU time at 1x (perf: exc_page_fault under swrast_dri.so on the GUI thread), and
// half the paint at 4x display density (GL 212-224 ms a paint against 119-126 with the heap kept).
// Keeping up to kKeptFreeHeapBytes of freed heap mapped lets the next paint reuse it. Setting it
// stops glibc from raising its mmap threshold as it goes, so that is set too, to the ceiling glibc
// would raise it to (32 MiB): blocks below it (a published frame's points, 1 MB) come from the heap
// and are reused; larger ones are mapped and returned when freed, so they do not stay.

#include <cstddef>

namespace wisp {

inline constexpr std::size_t kKeptFreeHeapBytes = std::size_t{ 256 } << 20;
inline constexpr std::size_t kMappedBlockBytes = std::size_t{ 32 } << 20; // and larger: mmap'd

// Keeps up to kKeptFreeHeapBytes of freed memory at the heap's top for reuse (glibc's
// M_TRIM_THRESHOLD), blocks from kMappedBlockBytes mapped (M_MMAP_THRESHOLD); nothing where the C
// library is not glibc. Call before anything allocates much.
void keepFreedHeapForReuse();

} // namespace wisp
