#include "uwgrasp/core/memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace uwgrasp {

void keep_freed_memory() {
#if defined(__GLIBC__)
  constexpr int kLarge = 1 << 30;  // serve every allocation below 1 GiB from the heap ...
  mallopt(M_MMAP_THRESHOLD, kLarge);
  mallopt(M_TRIM_THRESHOLD, kLarge);  // ... and keep up to 1 GiB of it when freed
#endif
}

}  // namespace uwgrasp
