#pragma once
// Bounding-volume hierarchy over a cloud's points for oriented-box queries: the collision check
// visits only the points near a candidate gripper instead of the whole cloud (the thesis checked
// every point against every candidate, 8.4, and named this as future work in 9.3).
//
// Layout: the points sorted along a Morton curve and cut into leaves of kLeafPoints consecutive
// points; every node has four children (four consecutive nodes of the level below, or four
// leaves) and stores their boxes lane by lane, so that one step of a walk tests all four with
// four-lane vector instructions. The tree is implicit: node j of a level has children 4j..4j+3.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

namespace uwgrasp::grasp {

inline constexpr std::uint32_t kLeafPoints = 8;

// The boxes of a node's four children as centre and half extents (what the box tests use), one
// lane per child; a missing child has NaN in its lane, which no test accepts.
struct BvhNode {
  alignas(16) float cx[4], cy[4], cz[4];
  alignas(16) float hx[4], hy[4], hz[4];
};

struct PointBvh {
  std::vector<Eigen::Vector3f> points;  // the cloud's points in BVH (Morton) order
  std::vector<std::uint32_t> index;     // index[k] = cloud index of points[k]
  // points again as coordinate arrays, NaN-padded to a whole number of leaves.
  std::vector<float> x, y, z;
  // levels[0]: the nodes whose children are leaves; each level above has a quarter as many;
  // levels.back() holds the root alone. Empty for an empty hierarchy.
  std::vector<std::vector<BvhNode>> levels;

  bool empty() const { return levels.empty(); }
  std::uint32_t top() const { return static_cast<std::uint32_t>(levels.size() - 1); }
  // Points under child `lane` of node j at `level`: [first, first + count).
  std::uint32_t first(std::uint32_t level, std::uint32_t j, int lane) const {
    return (4 * j + static_cast<std::uint32_t>(lane)) * (kLeafPoints << (2 * level));
  }
  std::uint32_t count(std::uint32_t level, std::uint32_t j, int lane) const;
};

// Builds the hierarchy. Throws Error for an empty cloud or a non-finite point.
PointBvh build_bvh(std::span<const Eigen::Vector3f> points);

}  // namespace uwgrasp::grasp
