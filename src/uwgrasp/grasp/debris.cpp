#include "uwgrasp/grasp/debris.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace uwgrasp::grasp {

namespace {
// A cell's integer coordinates packed in 63 bits (21 per axis, offset so negatives fit): scenes
// span at most 2^20 cells of `gap` from the camera along any axis (10 km at 1 cm).
std::uint64_t key(const Eigen::Vector3i& c) {
  constexpr std::int64_t off = 1 << 20;
  return (std::uint64_t(c.x() + off) << 42) | (std::uint64_t(c.y() + off) << 21) | std::uint64_t(c.z() + off);
}

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
  std::unordered_map<std::uint64_t, std::uint32_t> cells;
  std::vector<Eigen::Vector3i> coords;
  std::vector<std::uint32_t> cell_of(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3i c = (points[i] / gap).array().floor().cast<int>();
    const auto [it, fresh] = cells.try_emplace(key(c), std::uint32_t(coords.size()));
    if (fresh) coords.push_back(c);
    cell_of[i] = it->second;
  }
  UnionFind uf(coords.size());
  for (std::uint32_t a = 0; a < coords.size(); ++a)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          if (const auto it = cells.find(key(coords[a] + Eigen::Vector3i(dx, dy, dz))); it != cells.end())
            uf.join(a, it->second);
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
