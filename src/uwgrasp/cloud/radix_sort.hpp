#pragma once
// Stable LSD radix sort of (key, index) pairs, shared by the voxel grid and the point BVH.
#include <cstdint>
#include <vector>

namespace uwgrasp::cloud {

// Sorts keys (and idx alongside) on the low `bits` bits of the keys, 11 bits per pass: equal
// keys keep their input order, so anything summed in sorted order runs in a fixed order. All
// digit histograms come from one read pass; a pass whose digit is the same for every key is
// skipped.
void radix_sort(std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& idx, int bits);

}  // namespace uwgrasp::cloud
