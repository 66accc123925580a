#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <numeric>

#include "uwgrasp/cloud/radix_sort.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::cloud {

namespace {
// n items with a random key of `bits` bits at bit `lo` over their index; keys have many
// duplicates (low three bits clear) to exercise stability.
std::vector<std::uint64_t> items(std::size_t n, int lo, int bits) {
  Rng rng(5);
  std::vector<std::uint64_t> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = ((rng.below(std::uint64_t(1) << bits) & ~std::uint64_t(7)) << lo) | i;
  return out;
}

std::vector<std::uint64_t> sorted(std::size_t n, int lo, int bits, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::vector<std::uint64_t> out = items(n, lo, bits);
  radix_sort(out, lo, bits);
  return out;
}
}  // namespace

// The oracle is std::stable_sort on the key field; chunked parallel passes must give exactly its
// order at any thread count, and the bits outside the field travel with their key.
TEST(RadixSort, EqualsStableSortAtAnyThreadCount) {
  struct Field {
    int lo, bits;
  };
  for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(1000), std::size_t(32769), std::size_t(300000)}) {
    for (const Field f : {Field{32, 5}, Field{32, 30}, Field{32, 32}, Field{20, 44}}) {
      SCOPED_TRACE(std::to_string(n) + " items, " + std::to_string(f.bits) + " bits at " +
                   std::to_string(f.lo));
      std::vector<std::uint64_t> expect = items(n, f.lo, f.bits);
      std::stable_sort(expect.begin(), expect.end(),
                       [&](std::uint64_t a, std::uint64_t b) { return (a >> f.lo) < (b >> f.lo); });
      ASSERT_EQ(sorted(n, f.lo, f.bits, 1), expect);
      ASSERT_EQ(sorted(n, f.lo, f.bits, 2), expect);
    }
  }
}

// Bits above the field are not part of the key: they must not affect the order.
TEST(RadixSort, IgnoresBitsOutsideTheField) {
  std::vector<std::uint64_t> v = {(std::uint64_t(1) << 40) | (3u << 8) | 0u, (2u << 8) | 1u,
                                  (std::uint64_t(7) << 40) | (2u << 8) | 2u, (1u << 8) | 3u};
  radix_sort(v, 8, 4);
  std::vector<std::uint64_t> low;
  for (const auto x : v) low.push_back(x & 0xFF);
  EXPECT_EQ(low, (std::vector<std::uint64_t>{3, 1, 2, 0}));
}

}  // namespace uwgrasp::cloud
