#pragma once
// Counts the heap allocations (malloc, calloc, realloc and the aligned forms: operator new's,
// Eigen's, TBB's, the C libraries') while a function runs: how much a frame of a warm stream
// still asks of the allocator. Linking alloc_count.cpp replaces glibc's malloc family for the
// whole program with counting calls into glibc's own (not for sanitizer builds, which replace
// it themselves).
#include <cstddef>
#include <functional>

namespace uwgrasp::alloc_count {

struct Allocations {
  std::size_t calls = 0;
  std::size_t bytes = 0;
};

// The allocation calls and bytes asked that f makes (on any thread) while it runs.
Allocations count(const std::function<void()>& f);

}  // namespace uwgrasp::alloc_count
