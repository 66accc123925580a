#pragma once
// Bounding-volume hierarchy over a cloud's points for oriented-box queries: the collision check
// visits only the points near a candidate gripper instead of the whole cloud (the thesis checked
// every point against every candidate, 8.4, and named this as future work in 9.3).
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

namespace uwgrasp::grasp {

struct BvhNode {
  // Bounds of the node's points as centre and half extents (what the box tests use).
  Eigen::Vector3f centre = Eigen::Vector3f::Zero(), half = Eigen::Vector3f::Zero();
  std::uint32_t first = 0;  // first point (in BVH order) of the node
  std::uint32_t count = 0;  // number of points under the node
  std::uint32_t right = 0;  // index of the right child; 0 for a leaf (left child = this + 1)
  bool leaf() const { return right == 0; }
};

struct PointBvh {
  std::vector<Eigen::Vector3f> points;  // the cloud's points in BVH (Morton) order
  std::vector<std::uint32_t> index;     // index[k] = cloud index of points[k]
  std::vector<BvhNode> nodes;           // depth-first; nodes[0] is the root
};

// Builds the hierarchy: points sorted along a Morton curve, split at the middle, at most
// `leaf_size` points per leaf. Throws Error for an empty cloud or a non-finite point.
PointBvh build_bvh(std::span<const Eigen::Vector3f> points, std::uint32_t leaf_size = 8);

}  // namespace uwgrasp::grasp
