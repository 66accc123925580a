// Steps 2 and 3 of judging: the finger pads close on the target, and the contacts' force closure.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include "uwgrasp/eval/steps.hpp"

namespace uwgrasp::eval::detail {

namespace {
using V3 = Eigen::Vector3d;

// Pad positions (x along the approach, z across it) on a grid through the pad's centre.
struct PadGrid {
  std::vector<double> x, z;
};

std::vector<double> steps(double half, double spacing) {
  const int n = std::max(0, static_cast<int>(std::ceil(half / spacing - 1e-9)));
  std::vector<double> v;
  for (int i = -n; i <= n; ++i) v.push_back(n == 0 ? 0.0 : half * i / n);
  return v;
}

// Where a pad first touches: its travel from its start, what it touches, and the centre of its
// contact patch (x, z on the pad).
struct Touch {
  double t = std::numeric_limits<double>::infinity();
  int object = sim::kNoObject;
  Eigen::Vector2d patch = Eigen::Vector2d::Zero();
  bool found() const { return object != sim::kNoObject; }
};

using Polygon = std::vector<V3>;

// The part of a polygon (gripper frame) with sign * y <= bound.
Polygon clip_y(const Polygon& poly, double bound, double sign) {
  Polygon out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const V3& a = poly[i];
    const V3& b = poly[(i + 1) % poly.size()];
    const double da = bound - sign * a.y(), db = bound - sign * b.y();
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

// The centre of the surface a pad touches within the compliance of its first touch: the
// centroid of that surface projected on the pad (area-weighted), or of its vertices when it is
// edge-on to the pad.
Eigen::Vector2d patch_centre(std::span<const sim::ClippedTriangle> pieces, int target, double bound,
                             double sign) {
  double area = 0;
  Eigen::Vector2d weighted = Eigen::Vector2d::Zero(), vertices = Eigen::Vector2d::Zero();
  std::size_t count = 0;
  for (const sim::ClippedTriangle& c : pieces) {
    if (c.object != target) continue;
    const Polygon band = clip_y(c.polygon, bound, sign);
    for (std::size_t i = 0; i < band.size(); ++i) {
      const Eigen::Vector2d a(band[i].x(), band[i].z()), b(band[(i + 1) % band.size()].x(), band[(i + 1) % band.size()].z());
      const double cross = a.x() * b.y() - b.x() * a.y();  // shoelace: signed area and centroid
      area += 0.5 * cross;
      weighted += (a + b) * cross / 6.0;
      vertices += a, ++count;
    }
  }
  if (std::abs(area) > 1e-12) return weighted / area;
  return count > 0 ? Eigen::Vector2d(vertices / double(count)) : Eigen::Vector2d::Zero();
}

// The exact stop of both pads: the surfaces clipped to the pads' sweep (gripper frame), whose
// lowest point along y is where the left pad first touches and highest where the right one does
// (ties to the first piece in the clip order: by object, then triangle), with each contact
// patch's centre when the pad touches the target.
std::array<Touch, 2> first_touches(std::span<const sim::ClippedTriangle> pieces, double start,
                                   int target, double compliance) {
  std::array<Touch, 2> best;
  for (const sim::ClippedTriangle& c : pieces)
    for (const V3& p : c.polygon) {
      if (p.y() + start < best[0].t) best[0] = {p.y() + start, c.object};
      if (start - p.y() < best[1].t) best[1] = {start - p.y(), c.object};
    }
  if (best[0].object == target)
    best[0].patch = patch_centre(pieces, target, best[0].t - start + compliance, 1.0);
  if (best[1].object == target)
    best[1].patch = patch_centre(pieces, target, best[1].t - start + compliance, -1.0);
  return best;
}

// `first`, then the pad lines (x, z) ordered by distance from it, ties in grid order.
std::vector<Eigen::Vector2d> lines_from(const Eigen::Vector2d& first, const PadGrid& grid) {
  std::vector<Eigen::Vector2d> lines;
  for (const double x : grid.x)
    for (const double z : grid.z) lines.emplace_back(x, z);
  std::stable_sort(lines.begin(), lines.end(), [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - first).squaredNorm() < (b - first).squaredNorm();
  });
  lines.insert(lines.begin(), first);
  return lines;
}

// The line of action along the closing axis: through the midpoint of the pads' contact patches
// (where the grip's force acts: Dex-Net's line through the grasp centre, moved to where the
// object is), or the pad line nearest it that meets the target from both sides; with its two
// hits, false when no line does. That line is tried alone first: it is the answer for most grasps.
bool line_of_action(const sim::World& world, const Pose& T, double start, const PadGrid& grid,
                    const Eigen::Vector2d& centre, int target, sim::RayHit& left, sim::RayHit& right) {
  const std::vector<Eigen::Vector2d> lines = lines_from(centre, grid);
  const V3 y = T.linear().col(1);
  for (std::size_t first = 0, count = 1; first < lines.size(); first += count, count = lines.size() - first) {
    std::vector<sim::Ray> rays;
    for (std::size_t i = first; i < first + count; ++i) {
      rays.push_back({T * V3(lines[i].x(), -start, lines[i].y()), y, 2 * start});
      rays.push_back({T * V3(lines[i].x(), start, lines[i].y()), -y, 2 * start});
    }
    std::vector<sim::RayHit> hits(rays.size());
    sim::first_hits(world, rays, hits);
    for (std::size_t k = 0; k < hits.size(); k += 2)
      if (hits[k].hit && hits[k + 1].hit && hits[k].object == target && hits[k + 1].object == target) {
        left = hits[k], right = hits[k + 1];
        return true;
      }
  }
  return false;
}
}  // namespace

void close_pads(const sim::World& world, const grasp::Gripper& gripper, const Pose& T, int target,
                const JudgeConfig& cfg, Judgement& j) {
  const grasp::GripperConfig& gc = gripper.config;
  const double A = gc.max_aperture, tol = cfg.tolerance;
  // The pads start `tol` outside their faces, so a surface a pad already touches (within the
  // collision slack) is met at once; along their edges the same slack lets them slide past a
  // surface they graze, e.g. fingertips resting on the seafloor.
  const double start = 0.5 * A + tol;
  const sim::OrientedBox sweep{
      T.translation(), T.linear(),
      V3(std::max(0.0, 0.5 * gc.finger_length - tol), start, std::max(0.0, 0.5 * gc.finger_height - tol))};
  const std::vector<sim::ClippedTriangle> pieces = sim::clip_to_box(world, sweep, true);
  const auto [tl, tr] = first_touches(pieces, start, target, cfg.compliance);
  j = Judgement{};
  if (!tl.found() || !tr.found()) {
    j.verdict = Verdict::miss;
    return;
  }
  for (const Touch& t : {tl, tr})
    if (t.object != target) {
      j.verdict = Verdict::other_object;
      j.object = t.object;
      return;
    }
  j.object = target;
  const double travel = std::max(0.0, tl.t - tol) + std::max(0.0, tr.t - tol);
  j.width = std::max(0.0, A - travel);
  if (j.width > grasp::max_grasp_width(gripper)) {
    j.verdict = Verdict::too_wide;
    return;
  }
  if (j.width < gc.min_aperture) {
    j.verdict = Verdict::too_narrow;
    return;
  }
  const PadGrid grid{steps(0.5 * gc.finger_length, cfg.pad_spacing),
                     steps(0.5 * gc.finger_height, cfg.pad_spacing)};
  sim::RayHit cl, cr;
  if (!line_of_action(world, T, start, grid, 0.5 * (tl.patch + tr.patch), target, cl, cr)) {
    j.verdict = Verdict::miss;  // the pads touch the target only where no line crosses it twice
    return;
  }
  j.verdict = Verdict::closes;
  j.contacts[0] = cl.point, j.contacts[1] = cr.point;
  j.normals[0] = cl.normal, j.normals[1] = cr.normal;
  j.mu_min = force_closure_mu(cl.point, cl.normal, cr.point, cr.normal, T.linear().col(1));
}

}  // namespace uwgrasp::eval::detail
