#pragma once
// Counts the calls to the global operator new (every standard container's allocation; not
// Eigen's or TBB's own malloc calls) while a function runs: how much a frame of a warm stream
// still asks of the allocator. Linking alloc_count.cpp replaces operator new and delete for the
// whole program.
#include <cstddef>
#include <functional>

namespace uwgrasp::bench {

struct Allocations {
  std::size_t calls = 0;
  std::size_t bytes = 0;
};

// The operator new calls and bytes that f makes (on any thread) while it runs.
Allocations count_allocations(const std::function<void()>& f);

}  // namespace uwgrasp::bench
