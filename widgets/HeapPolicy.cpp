#include "widgets/HeapPolicy.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace wisp {

void keepFreedHeapForReuse()
{
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, static_cast<int>(kMappedBlockBytes));
    mallopt(M_TRIM_THRESHOLD, static_cast<int>(kKeptFreeHeapBytes));
#endif
}

} // namespace wisp
