#include "uwgrasp/grasp/debris.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

namespace uwgrasp::grasp {

namespace {
// A cell's integer coordinates packed in 63 bits (21 per axis, offset so negatives fit): scenes
// span at most 2^20 cells of `gap` from the camera along any axis (10 km at 1 cm).
std::uint64_t key(const Eigen::Vector3i& c) {
  constexpr std::int64_t off = 1 << 20;
  return (std::uint64_t(c.x() + off) << 42) | (std::uint64_t(c.y() + off) << 21) | std::uint64_t(c.z() + off);
}

// The occupied cells' keys, numbered in order of first appearance (deterministic): open
// addressing in one array, grown by doubling (std::unordered_map made a node per cell, ~1,000
// allocations a frame on mOSD_learn17's scene, the most of any one place in a detection).
class CellNumbers {
 public:
  // The number of `k`, given the next free number when `k` is new.
  std::uint32_t add(std::uint64_t k) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    Slot& s = slots_[probe(k)];
    if (s.id == kNone) s = {k, size_++};
    return s.id;
  }
  // The number of `k`, kNone when it was never added.
  std::uint32_t find(std::uint64_t k) const { return slots_.empty() ? kNone : slots_[probe(k)].id; }
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

 private:
  struct Slot {
    std::uint64_t key = 0;
    std::uint32_t id = kNone;
  };
  std::vector<Slot> slots_;  // none until the first add, then a power of two, at most half full
  std::uint32_t size_ = 0;
  int shift_ = 64;  // 64 - log2(slots_.size()) once there are slots

  // The slot of `k`, or the empty one where it would go. Fibonacci hashing: the product's top
  // bits, which every bit of the key reaches. Its low bits (taken, before, from bit 20 up) never
  // see the x axis (key bits 42 and up), so cells in one row along x shared a slot and a probe
  // walked the row (bench/kernels BM_Debris on the real mug frame: 21.3 -> 3.5 ms).
  std::size_t probe(std::uint64_t k) const {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = std::size_t((k * 0x9E3779B97F4A7C15ULL) >> shift_);; i = (i + 1) & mask)
      if (slots_[i].id == kNone || slots_[i].key == k) return i;
  }
  void grow() {
    std::vector<Slot> old(std::max<std::size_t>(64, 2 * slots_.size()));
    shift_ = 64 - std::countr_zero(old.size());
    old.swap(slots_);
    for (const Slot& s : old)
      if (s.id != kNone) slots_[probe(s.key)] = s;
  }
};

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

struct Extent {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f hi = -lo;
  bool rests = false;
};
}  // namespace

std::vector<char> debris(std::span<const Eigen::Vector3f> points, const std::optional<Eigen::Vector4f>& plane,
                         float gap, float size) {
  std::vector<char> out(points.size(), 0);
  if (!(size > 0.0f) || !(gap > 0.0f) || points.empty()) return out;
  // The occupied cells, numbered in order of first appearance (deterministic).
  CellNumbers cells;
  std::vector<Eigen::Vector3i> coords;
  std::vector<std::uint32_t> cell_of(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3i c = (points[i] / gap).array().floor().cast<int>();
    cell_of[i] = cells.add(key(c));
    if (cell_of[i] == coords.size()) coords.push_back(c);
  }
  UnionFind uf(coords.size());
  for (std::uint32_t a = 0; a < coords.size(); ++a)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          if (const std::uint32_t b = cells.find(key(coords[a] + Eigen::Vector3i(dx, dy, dz)));
              b != CellNumbers::kNone)
            uf.join(a, b);
  std::vector<Extent> extent(coords.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    Extent& e = extent[uf.find(cell_of[i])];
    e.lo = e.lo.cwiseMin(points[i]), e.hi = e.hi.cwiseMax(points[i]);
    if (plane && std::abs(plane->head<3>().dot(points[i]) + (*plane)[3]) <= gap) e.rests = true;
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Extent& e = extent[uf.find(cell_of[i])];
    out[i] = !e.rests && (e.hi - e.lo).norm() <= size;
  }
  return out;
}

}  // namespace uwgrasp::grasp
