#pragma once
// Internal to grasp/: what the BVH walk of feasibility.cpp and the brute-force reference of
// feasibility_brute.cpp share, so both name the same part and the same contacts.
#include <limits>

#include "uwgrasp/grasp/feasibility.hpp"
#include "uwgrasp/grasp/gripper.hpp"

namespace uwgrasp::grasp::closing_detail {

inline Reject collision(int part) { return static_cast<Reject>(int(Reject::collision_left_finger) + part); }

// The solid part holding a gripper-frame point, or none.
inline Reject solid_at(const Gripper& g, const Eigen::Vector3f& p) {
  if (!g.bounds.contains(p)) return Reject::none;
  for (int s = 0; s < kParts; ++s)
    if (g.solids[s].contains(p)) return collision(s);
  return Reject::none;
}

// Streaming closing-region statistics: count, nearest to the centre, extremes along y.
struct Closing {
  Check& out;
  float best = std::numeric_limits<float>::max(), lo = 0, hi = 0;
  void add(const Eigen::Vector3f& p, std::uint32_t i) {
    const float d = p.squaredNorm();
    if (out.inliers == 0) {
      best = d, lo = hi = p.y();
      out.nearest = out.left = out.right = i;
    } else {
      if (d < best || (d == best && i < out.nearest)) best = d, out.nearest = i;
      if (p.y() < lo || (p.y() == lo && i < out.left)) lo = p.y(), out.left = i;
      if (p.y() > hi || (p.y() == hi && i < out.right)) hi = p.y(), out.right = i;
    }
    ++out.inliers;
  }
  // True when no point in the gripper-frame box [lo, hi] can become the nearest point or an
  // extreme, so a node wholly inside the closing region only adds its count.
  bool cannot_improve(const Eigen::Vector3f& blo, const Eigen::Vector3f& bhi) const {
    if (out.inliers == 0 || !(blo.y() > lo) || !(bhi.y() < hi)) return false;
    const Eigen::Vector3f gap = blo.cwiseMax(-bhi).cwiseMax(0.0f);  // origin to the box
    return gap.squaredNorm() > best;
  }
  void finish(const Gripper& g) {
    if (out.inliers == 0) {
      out.reason = Reject::empty;
      return;
    }
    out.width = hi - lo;
    if (out.width < g.config.min_aperture) out.reason = Reject::too_narrow;
    else if (out.width > max_grasp_width(g)) out.reason = Reject::too_wide;
  }
};

}  // namespace uwgrasp::grasp::closing_detail
