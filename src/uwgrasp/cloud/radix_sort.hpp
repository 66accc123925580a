#pragma once
// Stable LSD radix sort of 64-bit items on a bit field, shared by the voxel grid and the point
// BVH. Callers pack a key above a point index in one word, so a pass moves 8 bytes per point
// instead of a separate key and index.
#include <cstdint>
#include <span>
#include <vector>

namespace uwgrasp::cloud {

// Sorts items on bits [lo, lo + bits) only, in place. Items with equal fields keep their input
// order, so anything summed in sorted order runs in a fixed order; the result does not depend
// on the thread count. One parallel pass over the whole array on the top 11 bits of the field,
// then each bucket sorts on the rest in cache; up to 32768 items, one thread sorts them all in
// cache.
void radix_sort(std::span<std::uint64_t> items, int lo, int bits);

// Its buffers, for a caller that sorts a stream of frames' items (capacities reused).
struct RadixScratch {
  std::vector<std::uint64_t> items;
  std::vector<std::uint32_t> histogram, starts;
};
void radix_sort(std::span<std::uint64_t> items, int lo, int bits, RadixScratch& scratch);

}  // namespace uwgrasp::cloud
