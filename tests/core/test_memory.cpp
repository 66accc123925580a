#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstddef>
#include <cstdlib>

#include "uwgrasp/core/memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace uwgrasp {
namespace {
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;  // the sanitizer's allocator replaces glibc's
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

// Allocates `bytes`, writes every page, frees it; returns the page faults that took.
long touch_and_free(std::size_t bytes) {
  const long before = minor_faults();
  // volatile: the compiler may not drop the writes, nor with them the allocation.
  auto* p = static_cast<volatile char*>(std::malloc(bytes));
  if (p == nullptr) return -1;
  for (std::size_t i = 0; i < bytes; i += 4096) p[i] = char(i);
  std::free(const_cast<char*>(p));
  return minor_faults() - before;
}
}  // namespace

// A frame's buffer freed stays in the heap, and the next frame's buffer of that size is served
// from it without faulting its pages in again (glibc would otherwise map such a buffer on its own
// and unmap it on free: 16,384 fresh pages for 64 MiB, every frame).
TEST(Memory, AFreedFrameBufferServesTheNextWithoutFreshPages) {
#if defined(__GLIBC__)
  if (kSanitized) GTEST_SKIP() << "the sanitizer's allocator is not glibc's";
  ASSERT_TRUE(keep_freed_memory());
  constexpr std::size_t kBytes = std::size_t(64) << 20;
  const long first = touch_and_free(kBytes);
  ASSERT_GE(first, 0);
  EXPECT_GE(mallinfo2().fordblks, kBytes) << "the freed buffer left the heap";
  const long again = touch_and_free(kBytes);
  EXPECT_LT(again, long(kBytes / 4096 / 16)) << "the second buffer faulted " << again << " pages in";
#else
  EXPECT_FALSE(keep_freed_memory());
#endif
}

}  // namespace uwgrasp
