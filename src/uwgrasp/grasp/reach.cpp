#include "uwgrasp/grasp/reach.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/debris.hpp"
#include "uwgrasp/grasp/lanes.hpp"

namespace uwgrasp::grasp {

namespace {
// Where a solid meets a point along the approach: the gripper at offset t (0 = the grasp pose,
// s = the standoff) holds gripper-frame point q at q + t x, so a point is hit for the t in
// [0, s] where the segment q + t x is inside the box (slab test, in the solid's own frame).
enum class Hit { none, on_approach, at_grasp };  // ordered: the worst is the largest

// A solid seen from one candidate: the map from L into the solid's own frame (p -> M p + o) and
// the approach there (d = R^T e_x, with its reciprocals), computed once per candidate and solid
// rather than per point: the test below runs for every point near the swept solid.
struct SolidView {
  Eigen::Matrix3f M;
  Eigen::Vector3f o, half, inv_d;
  std::array<bool, 3> across;  // the approach runs across axis i: no slab along it
  float s;

  SolidView(const Solid& b, const Candidate& c, float standoff) : half(b.half), s(standoff) {
    M = b.rotation.transpose() * c.rotation.transpose();
    o = -(M * c.position) - b.rotation.transpose() * b.centre;
    const Eigen::Vector3f d = b.rotation.row(0).transpose();
    for (int i = 0; i < 3; ++i) across[std::size_t(i)] = std::abs(d[i]) < 1e-9f, inv_d[i] = 1.0f / d[i];
  }

  // Where the solid meets L point p along the approach (slab test of p + t d, t in [0, s]).
  Hit hit(const Eigen::Vector3f& p_level) const {
    const Eigen::Vector3f p = M * p_level + o;
    float t0 = 0.0f, t1 = s;
    for (int i = 0; i < 3; ++i) {
      if (across[std::size_t(i)]) {
        if (std::abs(p[i]) > half[i]) return Hit::none;
        continue;
      }
      float a = (-half[i] - p[i]) * inv_d[i], c = (half[i] - p[i]) * inv_d[i];
      if (a > c) std::swap(a, c);
      t0 = std::max(t0, a), t1 = std::min(t1, c);
      if (t0 > t1) return Hit::none;
    }
    return t0 <= 0.0f ? Hit::at_grasp : Hit::on_approach;
  }
};

// The plane is convex and the sweep linear in t, so the corners at both ends decide.
Hit plane_hit(const Obstacles& o, const Solid& b, const Candidate& c, float s, float tol) {
  if (!o.has_plane) return Hit::none;
  // The lowest corner's height in closed form: n.(R_c (centre + R_b (+-half) - t x) + p_c) + d is
  // lowest at the signs against n_g = R_c^T n. Where it is clear of -tol by more than rounding can
  // move either form (1e-5 of the magnitudes summed), it decides; else the corners are computed
  // one by one, as the samplers' gate does for every draw (0.3 us a draw on the mug frame).
  const Eigen::Vector3f n = o.plane.head<3>(), n_g = c.rotation.transpose() * n;
  const Eigen::Vector3f spread = (b.rotation.transpose() * n_g).cwiseAbs().cwiseProduct(b.half);
  const float middle = n.dot(c.position) + o.plane[3] + n_g.dot(b.centre) - spread.sum();
  const float margin = 1e-5f * std::max(1.0f, n.norm()) *
                       (1.0f + std::abs(o.plane[3]) + c.position.cwiseAbs().sum() +
                        b.centre.cwiseAbs().sum() + b.half.sum() + s);
  const auto below = [&](float t) {
    const float lowest = middle - t * n_g.x();
    if (lowest > -tol + margin) return false;
    if (lowest < -tol - margin) return true;
    for (const auto& p : corners(b, c, t))
      if (n.dot(p) + o.plane[3] < -tol) return true;
    return false;
  };
  if (below(0.0f)) return Hit::at_grasp;
  return below(s) ? Hit::on_approach : Hit::none;
}

struct Query {
  const PointBvh& bvh;
  SolidView view;
  Eigen::Vector3f lo, hi;  // the swept solid's bounds in L
  lanes::V3 mid{}, half{};  // the same as centre and half extents, broadcast once for the walk
  // The swept solid's bounds in the candidate's gripper frame, and the map there: a rotated
  // hull's bounds in L hold far more of the scene than the solid does.
  lanes::Frame4 to_gripper;
  lanes::Box4 in_gripper;

  Query(const PointBvh& b, const Solid& solid, const Candidate& c, float s)
      : bvh(b), view(solid, c, s), to_gripper(c.rotation.transpose(), c.position) {
    lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max()), hi = -lo;
    for (float t : {0.0f, s})
      for (const auto& p : corners(solid, c, t)) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    mid = lanes::V3::splat(0.5f * (lo + hi)), half = lanes::V3::splat(0.5f * (hi - lo));
    const Eigen::Vector3f extent = solid.rotation.cwiseAbs() * solid.half;
    in_gripper = lanes::Box4::splat(solid.centre - extent - s * Eigen::Vector3f::UnitX(), solid.centre + extent);
  }

  // The worst hit under node j of `level`: at_grasp ends the search.
  Hit walk(std::uint32_t level, std::uint32_t j) const {
    const BvhNode& n = bvh.levels[level][j];
    const lanes::V3 c = lanes::load(n.cx, n.cy, n.cz), h = lanes::load(n.hx, n.hy, n.hz);
    const lanes::M4 near = lanes::near(c, h, mid, half) & lanes::overlap(to_gripper.boxes(c, h), in_gripper);
    Hit worst = Hit::none;
    for (int t = lanes::bits(near); t != 0 && worst != Hit::at_grasp; t &= t - 1) {
      const int lane = std::countr_zero(unsigned(t));
      worst = std::max(worst, level == 0 ? leaf(bvh.first(0, j, lane), bvh.count(0, j, lane))
                                         : walk(level - 1, 4 * j + std::uint32_t(lane)));
    }
    return worst;
  }

  Hit leaf(std::uint32_t first, std::uint32_t count) const {
    Hit worst = Hit::none;
    for (std::uint32_t k = first; k < first + count && worst != Hit::at_grasp; ++k)
      worst = std::max(worst, view.hit(bvh.points[k]));
    return worst;
  }
};

// The solids are judged in order: the first hit at the grasp pose names the reason; hits only on
// the way in make the candidate approach_blocked. `hit(k)` is solid k's worst hit.
template <class HitOf>
Reject verdict(std::span<const Solid> solids, HitOf hit) {
  bool blocked = false;
  for (std::size_t k = 0; k < solids.size(); ++k) {
    const Hit h = hit(k);
    if (h == Hit::at_grasp) return solids[k].at_grasp;
    blocked = blocked || h == Hit::on_approach;
  }
  return blocked ? Reject::approach_blocked : Reject::none;
}
}  // namespace

std::array<Eigen::Vector3f, 8> corners(const Solid& b, const Candidate& c, float t) {
  std::array<Eigen::Vector3f, 8> out;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3f sign((k & 1) ? 1.f : -1.f, (k & 2) ? 1.f : -1.f, (k & 4) ? 1.f : -1.f);
    const Eigen::Vector3f g = b.centre + b.rotation * sign.cwiseProduct(b.half) - t * Eigen::Vector3f::UnitX();
    out[static_cast<std::size_t>(k)] = c.rotation * g + c.position;
  }
  return out;
}

std::vector<Solid> vehicle_solids(const Gripper& g, const Frames& f, const ReachConfig& cfg) {
  if (!(cfg.hull_size.array() > 0.0).all() || !cfg.hull_size.allFinite())
    throw Error("grasp.reach.hull_size must be positive");
  if (!(cfg.standoff >= 0.0) || !(cfg.margin >= 0.0) || !(cfg.floor_tolerance >= 0.0) ||
      !(cfg.debris_size >= 0.0) || !(cfg.debris_gap > 0.0))
    throw Error("grasp.reach: standoff, margin, floor_tolerance and debris_size must be >= 0, debris_gap > 0");
  const Pose gripper_from_body = f.body_from_gripper.inverse();
  // The closing region's centre in the hull's own frame: inside it, nothing could be grasped.
  const Eigen::Vector3d centre_in_hull = f.body_from_gripper.translation() - cfg.hull_centre;
  if ((centre_in_hull.cwiseAbs().array() < 0.5 * cfg.hull_size.array()).all())
    throw Error("grasp.frames.gripper puts the gripper inside the hull (grasp.reach.hull_size, "
                "hull_centre): mount it outside the hull, or turn grasp.reach off");
  std::vector<Solid> out;
  Solid hull;
  hull.centre = (gripper_from_body * cfg.hull_centre).cast<float>();
  hull.rotation = gripper_from_body.linear().cast<float>();
  hull.half = (0.5 * cfg.hull_size + Eigen::Vector3d::Constant(cfg.margin)).cast<float>();
  out.push_back(hull);
  for (int k = 0; k < kParts; ++k) {
    const Box& b = g.solids[static_cast<std::size_t>(k)];
    Solid s;
    s.centre = b.centre(), s.half = b.half();
    s.at_grasp = Reject::scene_collision;
    out.push_back(s);
  }
  return out;
}

std::optional<Eigen::Vector4f> level_plane(const Surroundings& s, const Frames& f) {
  if (!s.has_plane) return std::nullopt;
  // n.p + d = 0 in C becomes n_L.p_L + d_L = 0 with n_L = R_LC n, d_L = d - n_L.t_LC.
  const Eigen::Vector3d n = f.level_from_camera.linear() * s.plane.head<3>().cast<double>();
  double d = s.plane[3] - n.dot(f.level_from_camera.translation());
  Eigen::Vector3d nn = n;
  if (nn.dot(f.level_from_camera.translation()) + d < 0.0) nn = -nn, d = -d;  // camera side +
  Eigen::Vector4f plane;
  plane << nn.cast<float>(), static_cast<float>(d);
  return plane;
}

Obstacles make_obstacles(const Surroundings& s, const Frames& f, const ReachConfig& cfg) {
  Obstacles o;
  const std::optional<Eigen::Vector4f> floor = s.has_plane ? std::optional(s.plane) : std::nullopt;
  const std::vector<char> drop = debris(s.points, floor, float(cfg.debris_gap), float(cfg.debris_size));
  std::vector<Eigen::Vector3f> solid;
  solid.reserve(s.points.size());
  for (std::size_t i = 0; i < s.points.size(); ++i)
    if (!drop[i]) solid.push_back(s.points[i]);
  if (!solid.empty()) o.bvh = build_bvh(points_to_level(solid, f));
  if (const auto plane = level_plane(s, f)) o.has_plane = true, o.plane = *plane;
  if (cfg.columns && o.has_plane && s.rests.size() == s.points.size()) {
    std::vector<Eigen::Vector3f> resting;
    for (std::size_t i = 0; i < s.points.size(); ++i)
      if (s.rests[i] && !drop[i]) resting.push_back(s.points[i]);
    o.columns =
        make_columns(points_to_level(resting, f), o.plane, s.points, f.level_from_camera.inverse());
  }
  return o;
}

Reject reach_check(const Obstacles& o, std::span<const Solid> solids, const Candidate& c,
                   const ReachConfig& cfg) {
  const float s = static_cast<float>(cfg.standoff);
  return verdict(solids, [&](std::size_t k) {
    const Hit plane = plane_hit(o, solids[k], c, s, static_cast<float>(cfg.floor_tolerance));
    if (plane == Hit::at_grasp) return plane;
    const Hit points =
        o.bvh.empty() ? plane : std::max(plane, Query(o.bvh, solids[k], c, s).walk(o.bvh.top(), 0));
    if (points == Hit::at_grasp || solids[k].at_grasp != Reject::scene_collision) return points;
    return cuts_column(o.columns, solids[k], c) ? Hit::at_grasp : points;
  });
}

Reject reach_plane_check(const Obstacles& o, std::span<const Solid> solids, const Candidate& c,
                         const ReachConfig& cfg) {
  return verdict(solids, [&](std::size_t k) {
    return plane_hit(o, solids[k], c, float(cfg.standoff), float(cfg.floor_tolerance));
  });
}

Reject reach_brute(std::span<const Eigen::Vector3f> level_points, const Obstacles& o,
                   std::span<const Solid> solids, const Candidate& c, const ReachConfig& cfg) {
  const float s = static_cast<float>(cfg.standoff);
  return verdict(solids, [&](std::size_t k) {
    Hit worst = plane_hit(o, solids[k], c, s, static_cast<float>(cfg.floor_tolerance));
    const SolidView view(solids[k], c, s);
    for (const auto& p : level_points) worst = std::max(worst, view.hit(p));
    if (solids[k].at_grasp == Reject::scene_collision && cuts_column_brute(o.columns, solids[k], c))
      return Hit::at_grasp;
    return worst;
  });
}

}  // namespace uwgrasp::grasp
