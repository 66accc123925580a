#pragma once
// The indices i < n for which a predicate holds, ascending, found in parallel: fixed chunks
// count them, then each writes its own from its offset (the predicate is evaluated twice instead
// of stored). The same list at any thread count. Used by the filters and the plane stage, whose
// sequential push_back loops over a 300k-point frame took a few ms each.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace uwgrasp::cloud {

// Into `out` (its capacity reused: a stream's frames ask the allocator for nothing once it
// holds a frame's list).
template <class Keep>
void indices_where(std::size_t n, Keep keep, std::vector<std::uint32_t>& out) {
  constexpr std::size_t kChunk = std::size_t(1) << 14;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  const auto end = [&](std::size_t c) { return std::min(n, (c + 1) * kChunk); };
  // The chunks' offsets on the stack up to 4M points (a 640 x 480 frame has 19 chunks).
  constexpr std::size_t kOnStack = 256;
  std::array<std::size_t, kOnStack + 1> local{};
  std::vector<std::size_t> heap(chunks > kOnStack ? chunks + 1 : 0, 0);
  std::size_t* start = chunks > kOnStack ? heap.data() : local.data();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      std::size_t count = 0;
      for (std::size_t i = c * kChunk; i < end(c); ++i) count += keep(i) ? 1 : 0;
      start[c + 1] = count;
    }
  });
  for (std::size_t c = 0; c < chunks; ++c) start[c + 1] += start[c];
  out.resize(start[chunks]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      std::uint32_t* at = out.data() + start[c];
      for (std::size_t i = c * kChunk; i < end(c); ++i)
        if (keep(i)) *at++ = static_cast<std::uint32_t>(i);
    }
  });
}

template <class Keep>
std::vector<std::uint32_t> indices_where(std::size_t n, Keep keep) {
  std::vector<std::uint32_t> out;
  indices_where(n, keep, out);
  return out;
}

}  // namespace uwgrasp::cloud
