#include "uwgrasp/cloud/radix_sort.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>

namespace uwgrasp::cloud {

namespace {
constexpr int kBits = 11;
constexpr std::size_t kBuckets = std::size_t(1) << kBits;
using Histogram = std::array<std::uint32_t, kBuckets>;
}  // namespace

// Each pass splits the input into fixed chunks: every chunk counts its digits in parallel, the
// chunk's output offsets are laid out bucket by bucket in chunk order, and every chunk scatters
// its own range in parallel. That is exactly the stable order of a sequential pass, so the
// result does not depend on the thread count.
void radix_sort(std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& idx, int bits) {
  const std::size_t n = keys.size();
  const std::size_t chunks = std::clamp<std::size_t>(n / 65536, 1, 16);
  const auto begin = [&](std::size_t c) { return n * c / chunks; };
  std::vector<Histogram> hist(chunks);
  std::vector<std::uint64_t> k2(n);
  std::vector<std::uint32_t> i2(n);
  for (int shift = 0; shift < bits; shift += kBits) {
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
      hist[c].fill(0);
      for (std::size_t j = begin(c); j < begin(c + 1); ++j) ++hist[c][(keys[j] >> shift) & (kBuckets - 1)];
    });
    // A pass whose digit is the same for every key changes nothing.
    std::size_t total_of_first = 0;
    for (std::size_t d = 0; d < kBuckets && total_of_first == 0; ++d)
      for (const Histogram& h : hist) total_of_first += h[d];
    if (total_of_first == n) continue;
    std::uint32_t at = 0;
    for (std::size_t d = 0; d < kBuckets; ++d)
      for (Histogram& h : hist) {
        const std::uint32_t count = h[d];
        h[d] = at;
        at += count;
      }
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
      Histogram& next = hist[c];
      for (std::size_t j = begin(c); j < begin(c + 1); ++j) {
        const std::uint32_t to = next[(keys[j] >> shift) & (kBuckets - 1)]++;
        k2[to] = keys[j], i2[to] = idx[j];
      }
    });
    keys.swap(k2), idx.swap(i2);
  }
}

}  // namespace uwgrasp::cloud
