#include "freeplay/core/memory.hpp"

#include <cstdlib>  // defines __GLIBC__ with glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace freeplay {

void keep_freed_memory_for_reuse() {
#if defined(__GLIBC__)
  // Above these a free would unmap (mmap threshold) or trim the heap's top (trim threshold); fixed values also stop
  // glibc's own adjustment of the mmap threshold, which still lets blocks between 128 KiB and 32 MiB be unmapped.
  constexpr int kMmapThresholdBytes = 256 << 20;
  constexpr int kTrimThresholdBytes = 1 << 30;
  mallopt(M_MMAP_THRESHOLD, kMmapThresholdBytes);
  mallopt(M_TRIM_THRESHOLD, kTrimThresholdBytes);
#endif
}

}  // namespace freeplay
