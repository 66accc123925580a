#include "uwgrasp/grasp/feasibility.hpp"

#include <tbb/parallel_for.h>

#include <array>
#include <limits>

namespace uwgrasp::grasp {

namespace {
// A candidate's frame: local = Rt * (world - t).
struct LocalFrame {
  Eigen::Matrix3f Rt, absRt;
  Eigen::Vector3f t;
  Eigen::Vector3f world_centre, world_half;  // world-axis bounds of the whole gripper
  Eigen::Vector3f closing_centre, closing_half;  // and of the closing region
  std::array<Eigen::Vector3f, kParts> part_centre, part_half;  // and of each solid part
};

LocalFrame local_frame(const Gripper& g, const Candidate& c) {
  LocalFrame f;
  f.Rt = c.rotation.transpose();
  f.absRt = f.Rt.cwiseAbs();
  f.t = c.position;
  f.world_centre = c.rotation * g.bounds.centre() + c.position;
  f.world_half = c.rotation.cwiseAbs() * g.bounds.half();
  f.closing_centre = c.rotation * g.closing.centre() + c.position;
  f.closing_half = c.rotation.cwiseAbs() * g.closing.half();
  for (int s = 0; s < kParts; ++s) {
    f.part_centre[s] = c.rotation * g.solids[s].centre() + c.position;
    f.part_half[s] = c.rotation.cwiseAbs() * g.solids[s].half();
  }
  return f;
}

bool overlaps(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, const Box& b) {
  return (lo.array() <= b.hi.array()).all() && (hi.array() >= b.lo.array()).all();
}
bool inside(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, const Box& b) {
  return (lo.array() >= b.lo.array()).all() && (hi.array() <= b.hi.array()).all();
}

Reject collision(int part) { return static_cast<Reject>(int(Reject::collision_left_finger) + part); }

// The solid part holding a gripper-frame point, or none.
Reject solid_at(const Gripper& g, const Eigen::Vector3f& p) {
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

struct Walker {
  const PointBvh& bvh;
  const Gripper& g;
  const LocalFrame& f;

  // The node's box in the gripper frame (conservative), or false when it is apart from the
  // gripper along a world axis or a gripper axis.
  bool local_box(const BvhNode& n, const Box& target, const Eigen::Vector3f& world_centre,
                 const Eigen::Vector3f& world_half, Eigen::Vector3f& lo, Eigen::Vector3f& hi) const {
    if (((n.centre - world_centre).cwiseAbs() - n.half - world_half).maxCoeff() > 0.0f) return false;
    const Eigen::Vector3f cl = f.Rt * (n.centre - f.t), hl = f.absRt * n.half;
    lo = cl - hl, hi = cl + hl;
    return overlaps(lo, hi, target);
  }

  // Phase 1: the first point in a solid part, if any.
  Reject solids(std::uint32_t i) const {
    const BvhNode& n = bvh.nodes[i];
    Eigen::Vector3f lo, hi;
    if (!local_box(n, g.bounds, f.world_centre, f.world_half, lo, hi)) return Reject::none;
    bool touches = false;
    for (int s = 0; s < kParts; ++s) {
      if (!overlaps(lo, hi, g.solids[s])) continue;
      if (inside(lo, hi, g.solids[s])) return collision(s);  // every point of the node is in it
      // Separated along a world axis after all?
      touches = touches ||
                ((n.centre - f.part_centre[s]).cwiseAbs() - n.half - f.part_half[s]).maxCoeff() <= 0.0f;
    }
    if (!touches) return Reject::none;
    if (n.leaf()) {
      for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
        const Reject r = solid_at(g, f.Rt * (bvh.points[k] - f.t));
        if (r != Reject::none) return r;
      }
      return Reject::none;
    }
    const Reject r = solids(i + 1);
    return r != Reject::none ? r : solids(n.right);
  }

  // Phase 2: the closing region's statistics (no point is in a solid part any more).
  void closing(std::uint32_t i, Closing& acc) const {
    const BvhNode& n = bvh.nodes[i];
    Eigen::Vector3f lo, hi;
    if (!local_box(n, g.closing, f.closing_centre, f.closing_half, lo, hi)) return;
    if (inside(lo, hi, g.closing) && acc.cannot_improve(lo, hi)) {
      acc.out.inliers += n.count;
      return;
    }
    if (!n.leaf()) {
      closing(i + 1, acc);
      closing(n.right, acc);
      return;
    }
    for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
      const Eigen::Vector3f p = f.Rt * (bvh.points[k] - f.t);
      if (g.closing.contains(p)) acc.add(p, bvh.index[k]);
    }
  }
};
}  // namespace

const char* reject_name(Reject r) {
  static const char* names[kRejectKinds] = {
      "feasible",       "collision_left_finger", "collision_right_finger",
      "collision_palm", "collision_body",        "empty",
      "too_narrow",     "too_wide",              "occluded",
      "not_antipodal",  "too_few_inliers",       "hull_collision",
      "scene_collision", "approach_blocked",     "cannot_hold"};
  return names[static_cast<int>(r)];
}

std::vector<Check> check_candidates(const PointBvh& bvh, const Gripper& g,
                                    std::span<const Candidate> candidates) {
  std::vector<Check> out(candidates.size());
  tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t i) {
    const LocalFrame f = local_frame(g, candidates[i]);
    const Walker w{bvh, g, f};
    out[i].reason = w.solids(0);
    if (out[i].reason != Reject::none) return;
    Closing acc{out[i]};
    w.closing(0, acc);
    acc.finish(g);
  });
  return out;
}

Check check_brute(std::span<const Eigen::Vector3f> points, const Gripper& g, const Candidate& c) {
  Check out;
  const Eigen::Matrix3f Rt = c.rotation.transpose();
  Closing acc{out};
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector3f p = Rt * (points[k] - c.position);
    const Reject r = solid_at(g, p);
    if (r != Reject::none) return Check{r};
    if (g.closing.contains(p)) acc.add(p, static_cast<std::uint32_t>(k));
  }
  acc.finish(g);
  return out;
}

std::vector<std::uint32_t> closing_points(std::span<const Eigen::Vector3f> points,
                                          const Gripper& g, const Candidate& c) {
  std::vector<std::uint32_t> out;
  const Eigen::Matrix3f Rt = c.rotation.transpose();
  for (std::size_t k = 0; k < points.size(); ++k)
    if (g.closing.contains(Rt * (points[k] - c.position))) out.push_back(static_cast<std::uint32_t>(k));
  return out;
}

RejectCounts count_rejections(std::span<const Check> checks) {
  RejectCounts counts{};
  for (const Check& c : checks) ++counts[static_cast<int>(c.reason)];
  return counts;
}

}  // namespace uwgrasp::grasp
