#include "alloc_count.hpp"

#include <atomic>
#include <cerrno>
#include <cstddef>

// glibc's own allocator under its exported names: the counting functions below forward to it,
// so that every block, whoever asked for it, comes from one allocator and any of them frees it.
extern "C" {
void* __libc_malloc(std::size_t n);
void* __libc_calloc(std::size_t count, std::size_t n);
void* __libc_realloc(void* p, std::size_t n);
void* __libc_memalign(std::size_t align, std::size_t n);
void __libc_free(void* p);
}

namespace {
std::atomic<std::size_t> g_calls{0}, g_bytes{0};

void note(std::size_t n) {
  g_calls.fetch_add(1, std::memory_order_relaxed);
  g_bytes.fetch_add(n, std::memory_order_relaxed);
}
}  // namespace

// Replacing malloc and its family in the executable catches every heap allocation of the
// process: libstdc++'s operator new (every standard container), Eigen's dynamic matrices, TBB's
// and the C libraries'. Counting operator new alone missed Eigen's: ~1,000 a detection frame
// that went unseen until heaptrack showed them.
extern "C" {
void* malloc(std::size_t n) {
  note(n);
  return __libc_malloc(n);
}
void* calloc(std::size_t count, std::size_t n) {
  note(count * n);
  return __libc_calloc(count, n);
}
void* realloc(void* p, std::size_t n) {
  note(n);
  return __libc_realloc(p, n);
}
void* memalign(std::size_t align, std::size_t n) {
  note(n);
  return __libc_memalign(align, n);
}
void* aligned_alloc(std::size_t align, std::size_t n) {
  note(n);
  return __libc_memalign(align, n);
}
int posix_memalign(void** out, std::size_t align, std::size_t n) {
  note(n);
  void* p = __libc_memalign(align, n);
  if (p == nullptr) return ENOMEM;
  *out = p;
  return 0;
}
void free(void* p) { __libc_free(p); }
}

namespace uwgrasp::alloc_count {

Allocations count(const std::function<void()>& f) {
  const std::size_t c0 = g_calls.load(), b0 = g_bytes.load();
  f();
  return {g_calls.load() - c0, g_bytes.load() - b0};
}

}  // namespace uwgrasp::alloc_count
