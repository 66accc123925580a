#include "uwgrasp/core/memory.hpp"

// <cstdlib> first: glibc defines __GLIBC__ in <features.h>, which the C library's headers
// include. Tested before any of them, the macro is undefined and the policy below compiled to
// nothing (as it did until 2026-11-27: every frame of a stream faulted its buffers in again).
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace uwgrasp {

bool keep_freed_memory() {
#if defined(__GLIBC__)
  // Serve every allocation below 1 GiB from the heap, and keep up to 1 GiB of it when freed.
  constexpr int kLarge = 1 << 30;
  const bool mmap_set = mallopt(M_MMAP_THRESHOLD, kLarge) == 1;
  const bool trim_set = mallopt(M_TRIM_THRESHOLD, kLarge) == 1;
  return mmap_set && trim_set;
#else
  return false;
#endif
}

}  // namespace uwgrasp
