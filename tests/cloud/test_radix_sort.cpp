#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <numeric>

#include "uwgrasp/cloud/radix_sort.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::cloud {

namespace {
// Sorted by radix_sort under a thread limit; keys have many duplicates to exercise stability.
std::pair<std::vector<std::uint64_t>, std::vector<std::uint32_t>> sorted(std::size_t n, int bits,
                                                                         int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Rng rng(5);
  std::vector<std::uint64_t> keys(n);
  for (auto& k : keys) k = rng.below(std::uint64_t(1) << bits) & ~std::uint64_t(7);
  std::vector<std::uint32_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0u);
  radix_sort(keys, idx, bits);
  return {keys, idx};
}
}  // namespace

// The oracle is std::stable_sort; chunked parallel passes must give exactly its order.
TEST(RadixSort, EqualsStableSortAtAnyThreadCount) {
  for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(1000), std::size_t(300000)}) {
    for (const int bits : {5, 30, 40}) {
      SCOPED_TRACE(std::to_string(n) + " keys, " + std::to_string(bits) + " bits");
      const auto one = sorted(n, bits, 1), two = sorted(n, bits, 2);
      Rng rng(5);
      std::vector<std::uint64_t> keys(n);
      for (auto& k : keys) k = rng.below(std::uint64_t(1) << bits) & ~std::uint64_t(7);
      std::vector<std::uint32_t> expect(n);
      std::iota(expect.begin(), expect.end(), 0u);
      std::stable_sort(expect.begin(), expect.end(),
                       [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
      ASSERT_EQ(one.second, expect);
      ASSERT_EQ(two.second, expect);
      ASSERT_TRUE(std::is_sorted(one.first.begin(), one.first.end()));
    }
  }
}

}  // namespace uwgrasp::cloud
