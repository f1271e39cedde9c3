#include "edgevio/common/process_memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace edgevio {

bool keepFreedMemory() {
#if defined(__GLIBC__)
  constexpr int kMmapThreshold = 64 << 20;  // glibc's dynamic threshold stops at 32 MiB
  constexpr int kTrimThreshold = 256 << 20;
  return mallopt(M_MMAP_THRESHOLD, kMmapThreshold) == 1 && mallopt(M_TRIM_THRESHOLD, kTrimThreshold) == 1;
#else
  return false;
#endif
}

}  // namespace edgevio
