#include "uwgrasp/grasp/bvh.hpp"

#include <algorithm>
#include <string>

#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/cloud/radix_sort.hpp"

namespace uwgrasp::grasp {

namespace {
// Spreads the low 10 bits of v so that two zero bits separate each pair of bits.
std::uint64_t spread(std::uint64_t v) {
  v &= 0x3FF;
  v = (v | (v << 16)) & 0x030000FF;
  v = (v | (v << 8)) & 0x0300F00F;
  v = (v | (v << 4)) & 0x030C30C3;
  v = (v | (v << 2)) & 0x09249249;
  return v;
}

std::uint64_t morton(const Eigen::Vector3f& p, const Eigen::Vector3f& lo, const Eigen::Vector3f& scale) {
  const Eigen::Vector3f q = ((p - lo).cwiseProduct(scale)).cwiseMax(0.0f).cwiseMin(1023.0f);
  return spread(std::uint64_t(q.x())) | (spread(std::uint64_t(q.y())) << 1) |
         (spread(std::uint64_t(q.z())) << 2);
}

constexpr float kPad = 1e-5f;  // m

struct Bounds {
  Eigen::Vector3f lo, hi;
};

// Builds the subtree over points [first, first + count) at nodes.size(); returns its bounds.
Bounds build(PointBvh& b, std::uint32_t first, std::uint32_t count, std::uint32_t leaf) {
  const auto at = static_cast<std::uint32_t>(b.nodes.size());
  b.nodes.push_back(BvhNode{});
  BvhNode node;
  node.first = first, node.count = count;
  Bounds box{b.points[first], b.points[first]};
  if (count <= leaf) {
    for (std::uint32_t k = first + 1; k < first + count; ++k) {
      box.lo = box.lo.cwiseMin(b.points[k]);
      box.hi = box.hi.cwiseMax(b.points[k]);
    }
  } else {
    const std::uint32_t half = count / 2;
    const Bounds left = build(b, first, half, leaf);
    node.right = static_cast<std::uint32_t>(b.nodes.size());
    const Bounds right = build(b, first + half, count - half, leaf);
    box = {left.lo.cwiseMin(right.lo), left.hi.cwiseMax(right.hi)};
  }
  node.centre = 0.5f * (box.lo + box.hi);
  // Padded so that rounding in the box tests can only keep a node, never drop one.
  node.half = 0.5f * (box.hi - box.lo) + Eigen::Vector3f::Constant(kPad);
  b.nodes[at] = node;
  return box;
}
}  // namespace

PointBvh build_bvh(std::span<const Eigen::Vector3f> points, std::uint32_t leaf_size) {
  if (points.empty()) throw Error("cannot build a BVH over an empty cloud");
  if (leaf_size == 0) throw Error("BVH leaf size must be positive");
  Eigen::Vector3f lo = points[0], hi = points[0];
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!is_finite(points[i]))
      throw Error("BVH: point " + std::to_string(i) + " is not finite");
    lo = lo.cwiseMin(points[i]);
    hi = hi.cwiseMax(points[i]);
  }
  const Eigen::Vector3f extent = (hi - lo).cwiseMax(1e-12f);
  const Eigen::Vector3f scale = Eigen::Vector3f::Constant(1023.0f).cwiseQuotient(extent);
  std::vector<std::uint64_t> keys(points.size());
  PointBvh b;
  b.index.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    keys[i] = morton(points[i], lo, scale);
    b.index[i] = static_cast<std::uint32_t>(i);
  }
  cloud::radix_sort(keys, b.index, 30);
  b.points.resize(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) b.points[k] = points[b.index[k]];
  b.nodes.reserve(2 * points.size() / std::max<std::uint32_t>(1, leaf_size / 2) + 1);
  build(b, 0, static_cast<std::uint32_t>(points.size()), leaf_size);
  return b;
}

}  // namespace uwgrasp::grasp
