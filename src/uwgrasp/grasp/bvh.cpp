#include "uwgrasp/grasp/bvh.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "uwgrasp/cloud/radix_sort.hpp"
#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::grasp {

namespace {
// The low 10 bits of v spread so that two zero bits separate each pair of bits, for every v:
// three table loads per Morton code instead of three rounds of shifts and masks.
constexpr std::array<std::uint32_t, 1024> make_spread() {
  std::array<std::uint32_t, 1024> t{};
  for (std::uint32_t v = 0; v < 1024; ++v)
    for (int b = 0; b < 10; ++b) t[v] |= ((v >> b) & 1u) << (3 * b);
  return t;
}
constexpr std::array<std::uint32_t, 1024> kSpread = make_spread();

std::uint64_t morton(const Eigen::Vector3f& p, const Eigen::Vector3f& lo, const Eigen::Vector3f& scale) {
  const Eigen::Vector3f q = ((p - lo).cwiseProduct(scale)).cwiseMax(0.0f).cwiseMin(1023.0f);
  return std::uint64_t(kSpread[std::size_t(static_cast<int>(q.x()))]) |
         (std::uint64_t(kSpread[std::size_t(static_cast<int>(q.y()))]) << 1) |
         (std::uint64_t(kSpread[std::size_t(static_cast<int>(q.z()))]) << 2);
}

constexpr float kPad = 1e-5f;  // m
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr std::size_t kGrain = 256;

struct Bounds {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(kNaN), hi = Eigen::Vector3f::Constant(kNaN);
  bool valid() const { return !std::isnan(lo.x()); }
  void add(const Eigen::Vector3f& l, const Eigen::Vector3f& h) {
    const bool first = !valid();
    lo = first ? l : lo.cwiseMin(l);
    hi = first ? h : hi.cwiseMax(h);
  }
};

// Writes child box b into `lane` of node n, padded so that rounding in the box tests can only
// keep a child, never drop one; a missing child keeps NaN.
void set_lane(BvhNode& n, int lane, const Bounds& b) {
  const Eigen::Vector3f c = 0.5f * (b.lo + b.hi);
  const Eigen::Vector3f h = 0.5f * (b.hi - b.lo) + Eigen::Vector3f::Constant(kPad);
  n.cx[lane] = c.x(), n.cy[lane] = c.y(), n.cz[lane] = c.z();
  n.hx[lane] = h.x(), n.hy[lane] = h.y(), n.hz[lane] = h.z();
}

// One level of nodes over `children` boxes (leaves or the level below); returns the nodes' boxes.
std::vector<Bounds> make_level(const std::vector<Bounds>& children, std::vector<BvhNode>& nodes) {
  const std::size_t n = (children.size() + 3) / 4;
  nodes.resize(n);
  std::vector<Bounds> out(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const auto& r) {
    for (std::size_t j = r.begin(); j < r.end(); ++j) {
      BvhNode& node = nodes[j];
      for (float* a : {node.cx, node.cy, node.cz, node.hx, node.hy, node.hz}) std::fill_n(a, 4, kNaN);
      for (int lane = 0; lane < 4 && 4 * j + std::size_t(lane) < children.size(); ++lane) {
        const Bounds& b = children[4 * j + std::size_t(lane)];
        set_lane(node, lane, b);
        out[j].add(b.lo, b.hi);
      }
    }
  });
  return out;
}

// Sorts the points along the Morton curve of their bounding box into b.points / b.index.
void morton_order(std::span<const Eigen::Vector3f> points, PointBvh& b) {
  Eigen::Vector3f lo = points[0], hi = points[0];
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!is_finite(points[i])) throw Error("BVH: point " + std::to_string(i) + " is not finite");
    lo = lo.cwiseMin(points[i]);
    hi = hi.cwiseMax(points[i]);
  }
  const Eigen::Vector3f extent = (hi - lo).cwiseMax(1e-12f);
  const Eigen::Vector3f scale = Eigen::Vector3f::Constant(1023.0f).cwiseQuotient(extent);
  // The 30-bit Morton code above the 32-bit point index: one word per point to sort.
  std::vector<std::uint64_t> items(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) items[i] = (morton(points[i], lo, scale) << 32) | i;
  });
  cloud::radix_sort(items, 32, 30);
  b.index.resize(points.size());
  for (std::size_t i = 0; i < items.size(); ++i) b.index[i] = static_cast<std::uint32_t>(items[i]);
}
}  // namespace

std::uint32_t PointBvh::count(std::uint32_t level, std::uint32_t j, int lane) const {
  const std::uint32_t begin = first(level, j, lane), n = static_cast<std::uint32_t>(points.size());
  return begin >= n ? 0 : std::min(n - begin, kLeafPoints << (2 * level));
}

PointBvh build_bvh(std::span<const Eigen::Vector3f> points) {
  if (points.empty()) throw Error("cannot build a BVH over an empty cloud");
  if (points.size() >= (std::size_t(1) << 30)) throw Error("BVH: more than 2^30 points");
  PointBvh b;
  morton_order(points, b);
  const std::size_t n = points.size(), leaves = (n + kLeafPoints - 1) / kLeafPoints;
  b.points.resize(n);
  for (auto* v : {&b.x, &b.y, &b.z}) v->assign(leaves * kLeafPoints, kNaN);
  std::vector<Bounds> boxes(leaves);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves, kGrain), [&](const auto& r) {
    for (std::size_t leaf = r.begin(); leaf < r.end(); ++leaf)
      for (std::size_t k = leaf * kLeafPoints; k < std::min(n, (leaf + 1) * kLeafPoints); ++k) {
        const Eigen::Vector3f& p = points[b.index[k]];
        b.points[k] = p;
        b.x[k] = p.x(), b.y[k] = p.y(), b.z[k] = p.z();
        boxes[leaf].add(p, p);
      }
  });
  do {
    b.levels.emplace_back();
    boxes = make_level(boxes, b.levels.back());
  } while (boxes.size() > 1);
  return b;
}

}  // namespace uwgrasp::grasp
