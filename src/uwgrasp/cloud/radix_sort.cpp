#include "uwgrasp/cloud/radix_sort.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace uwgrasp::cloud {

namespace {
// The first pass sorts on the top kTopBits of the field over the whole array; each of its
// buckets then sorts on the rest of the field in place, where it fits in cache, in passes of at
// most kLocalBits (or by insertion when it is small). One pass over memory instead of two or three.
constexpr int kTopBits = 11;
constexpr int kLocalBits = 8;
constexpr std::size_t kInsertion = 32;
// Below this many items one thread sorts the whole array in cache with LSD passes: the parallel
// pass's tasks and its 2048-bucket tables cost more than they save (the BVH of a 2.5 mm voxel
// object, ~6k points, sorted 4x faster this way).
constexpr std::size_t kSequential = std::size_t(1) << 15;
constexpr int kSequentialBits = 11;  // a 30-bit Morton code in three passes; 8 KB of counts

struct Pass {
  int shift;
  std::uint64_t mask;
  std::size_t digit(std::uint64_t item) const { return std::size_t((item >> shift) & mask); }
};

Pass field(int shift, int width) { return {shift, (std::uint64_t(1) << width) - 1}; }

// One stable pass src -> dst over the whole array. Fixed chunks count their digits in parallel,
// each chunk's output offsets are laid out bucket by bucket in chunk order, and every chunk
// scatters its own range in parallel: exactly the order of a sequential pass at any thread
// count. Returns where each bucket starts in dst (plus n at the end).
void global_pass(const std::uint64_t* src, std::uint64_t* dst, std::size_t n, Pass pass,
                 std::vector<std::uint32_t>& hist, std::vector<std::uint32_t>& starts) {
  const std::size_t buckets = pass.mask + 1, chunks = std::clamp<std::size_t>(n / 32768, 1, 16);
  const auto begin = [&](std::size_t c) { return n * c / chunks; };
  hist.assign(chunks * buckets, 0u), starts.resize(buckets + 1);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    std::uint32_t* h = &hist[c * buckets];
    for (std::size_t j = begin(c); j < begin(c + 1); ++j) ++h[pass.digit(src[j])];
  });
  std::uint32_t at = 0;
  for (std::size_t d = 0; d < buckets; ++d) {
    starts[d] = at;
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::uint32_t count = hist[c * buckets + d];
      hist[c * buckets + d] = at;
      at += count;
    }
  }
  starts[buckets] = at;
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    std::uint32_t* next = &hist[c * buckets];
    for (std::size_t j = begin(c); j < begin(c + 1); ++j) dst[next[pass.digit(src[j])]++] = src[j];
  });
}

// Stable sort of m items on `pass`'s field by insertion; for buckets of a few dozen items.
void insertion_sort(std::uint64_t* a, std::size_t m, Pass pass) {
  const auto key = [&](std::uint64_t x) { return (x >> pass.shift) & pass.mask; };
  for (std::size_t i = 1; i < m; ++i) {
    const std::uint64_t x = a[i];
    std::size_t j = i;
    for (; j > 0 && key(a[j - 1]) > key(x); --j) a[j] = a[j - 1];
    a[j] = x;
  }
}

// Sorts one bucket, now in `from`, on bits [lo, lo + bits) into `to` (from is scratch), in
// passes of at most kWidth bits.
template <int kWidth>
void local_sort(std::uint64_t* from, std::uint64_t* to, std::size_t m, int lo, int bits) {
  if (m <= kInsertion || bits <= 0) {
    std::copy_n(from, m, to);
    if (bits > 0) insertion_sort(to, m, field(lo, bits));
    return;
  }
  const int passes = (bits + kWidth - 1) / kWidth, width = (bits + passes - 1) / passes;
  std::uint64_t *src = from, *dst = to;
  for (int p = 0; p < passes; ++p) {
    const Pass pass = field(lo + p * width, std::min(width, bits - p * width));
    std::array<std::uint32_t, std::size_t(1) << kWidth> next{};
    for (std::size_t j = 0; j < m; ++j) ++next[pass.digit(src[j])];
    if (next[pass.digit(src[0])] == m) continue;  // one digit for all: the pass changes nothing
    std::uint32_t at = 0;
    for (std::size_t d = 0; d <= pass.mask; ++d) at += std::exchange(next[d], at);
    for (std::size_t j = 0; j < m; ++j) dst[next[pass.digit(src[j])]++] = src[j];
    std::swap(src, dst);
  }
  if (src != to) std::copy_n(src, m, to);
}
}  // namespace

void radix_sort(std::span<std::uint64_t> items, int lo, int bits) {
  RadixScratch scratch;
  radix_sort(items, lo, bits, scratch);
}

void radix_sort(std::span<std::uint64_t> items, int lo, int bits, RadixScratch& buffers) {
  const std::size_t n = items.size();
  if (n < 2 || bits <= 0) return;
  buffers.items.resize(n);  // only written before it is read: no fill
  std::uint64_t* const scratch = buffers.items.data();
  if (n <= kSequential) {
    std::copy_n(items.data(), n, scratch);
    local_sort<kSequentialBits>(scratch, items.data(), n, lo, bits);
    return;
  }
  const int top = std::min(bits, kTopBits), rest = bits - top;
  std::vector<std::uint32_t>& starts = buffers.starts;
  global_pass(items.data(), scratch, n, field(lo + rest, top), buffers.histogram, starts);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, starts.size() - 1, 16), [&](const auto& r) {
    for (std::size_t d = r.begin(); d != r.end(); ++d) {
      const std::size_t a = starts[d], m = starts[d + 1] - a;
      local_sort<kLocalBits>(scratch + a, items.data() + a, m, lo, rest);
    }
  });
}

}  // namespace uwgrasp::cloud
