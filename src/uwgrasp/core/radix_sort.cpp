#include "uwgrasp/core/radix_sort.hpp"

#include <algorithm>
#include <array>

namespace uwgrasp {

void radix_sort(std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& idx, int bits) {
  const int passes = (bits + 10) / 11;
  std::vector<std::array<std::uint32_t, 2049>> hist(passes, std::array<std::uint32_t, 2049>{});
  for (auto k : keys)
    for (int p = 0; p < passes; ++p) ++hist[p][((k >> (11 * p)) & 2047) + 1];
  std::vector<std::uint64_t> k2(keys.size());
  std::vector<std::uint32_t> i2(idx.size());
  for (int p = 0; p < passes; ++p) {
    const int shift = 11 * p;
    auto& start = hist[p];
    if (std::find(start.begin(), start.end(), keys.size()) != start.end()) continue;
    for (std::size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
    for (std::size_t j = 0; j < keys.size(); ++j) {
      const std::uint32_t to = start[(keys[j] >> shift) & 2047]++;
      k2[to] = keys[j], i2[to] = idx[j];
    }
    keys.swap(k2), idx.swap(i2);
  }
}

}  // namespace uwgrasp
