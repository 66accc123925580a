#include "uwgrasp/grasp/columns.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "uwgrasp/grasp/reach.hpp"

namespace uwgrasp::grasp {

namespace {
constexpr std::size_t kMaxCells = std::size_t(1) << 22;

// Bounds of points' feet in the plane's (u, v) coordinates.
struct Rect {
  float lo_u = std::numeric_limits<float>::max(), lo_v = lo_u, hi_u = -lo_u, hi_v = -lo_u;
  void add(float a, float b) {
    lo_u = std::min(lo_u, a), hi_u = std::max(hi_u, a), lo_v = std::min(lo_v, b), hi_v = std::max(hi_v, b);
  }
};

// Solid's own frame from L at the grasp pose: p_box = M p + o.
struct BoxFrame {
  Eigen::Matrix3f M;
  Eigen::Vector3f o, down;  // down: the column's direction (-n) in the box's frame
  BoxFrame(const Solid& s, const Candidate& c, const Eigen::Vector3f& n) {
    M = s.rotation.transpose() * c.rotation.transpose();
    o = -(M * c.position) - s.rotation.transpose() * s.centre;
    down = -(M * n);
  }
};

// Whether the segment p - t n, t in [0, h], meets the box (slab test in its frame) where the
// camera could not see: tested every `step` of the stretch inside the box.
bool segment_hits(const Columns& cols, const BoxFrame& f, const Eigen::Vector3f& half, const Eigen::Vector3f& p,
                  float h) {
  const Eigen::Vector3f q = f.M * p + f.o;
  float t0 = 0.0f, t1 = h;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(f.down[i]) < 1e-9f) {
      if (std::abs(q[i]) > half[i]) return false;
      continue;
    }
    float a = (-half[i] - q[i]) / f.down[i], b = (half[i] - q[i]) / f.down[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  const Eigen::Vector3f n = cols.plane.head<3>();
  for (float t = t0;; t = std::min(t + cols.step, t1)) {
    const Eigen::Vector3f c = cols.camera_rotation * (p - t * n) + cols.camera_offset;
    if (c.z() > 0.0f && cols.seen.at(c.x() / c.z(), c.y() / c.z()) < c.z() - cols.tolerance) return true;
    if (t >= t1) return false;
  }
}
}  // namespace

Columns make_columns(std::span<const Eigen::Vector3f> level_points, const Eigen::Vector4f& plane,
                     std::span<const Eigen::Vector3f> seen, const Pose& camera_from_level, float cell) {
  Columns out;
  out.plane = plane;
  out.camera_rotation = camera_from_level.linear().cast<float>();
  out.camera_offset = camera_from_level.translation().cast<float>();
  const Eigen::Vector3f n = plane.head<3>();
  out.u = n.unitOrthogonal(), out.v = n.cross(out.u);
  std::vector<Eigen::Vector3f> above;
  for (const Eigen::Vector3f& p : level_points)
    if (n.dot(p) + plane[3] > 0.0f) above.push_back(p);
  if (above.empty()) return out;
  Rect r;
  for (const Eigen::Vector3f& p : above) r.add(out.u.dot(p), out.v.dot(p));
  const float lo_u = r.lo_u, lo_v = r.lo_v, hi_u = r.hi_u, hi_v = r.hi_v;
  // Coarser cells for a scene too wide for the grid.
  while (double(hi_u - lo_u) / cell * double(hi_v - lo_v) / cell > double(kMaxCells)) cell *= 2.0f;
  out.cell = cell, out.u0 = lo_u, out.v0 = lo_v;
  out.nu = int((hi_u - lo_u) / cell) + 1, out.nv = int((hi_v - lo_v) / cell) + 1;
  const auto cell_of = [&](const Eigen::Vector3f& p) {
    const int i = std::min(out.nu - 1, int((out.u.dot(p) - lo_u) / cell));
    const int j = std::min(out.nv - 1, int((out.v.dot(p) - lo_v) / cell));
    return std::size_t(j) * std::size_t(out.nu) + std::size_t(i);
  };
  out.start.assign(std::size_t(out.nu) * std::size_t(out.nv) + 1, 0);
  for (const Eigen::Vector3f& p : above) ++out.start[cell_of(p) + 1];
  for (std::size_t k = 1; k < out.start.size(); ++k) out.start[k] += out.start[k - 1];
  std::vector<std::uint32_t> next(out.start.begin(), out.start.end() - 1);
  out.points.resize(above.size());
  out.height.resize(above.size());
  for (const Eigen::Vector3f& p : above) {
    const std::uint32_t at = next[cell_of(p)]++;
    out.points[at] = p, out.height[at] = n.dot(p) + plane[3];
  }
  out.seen = make_depth_map(seen, 0.003f);  // the object's shape's bins (ShapeConfig::resolution)
  return out;
}

bool cuts_column(const Columns& cols, const Solid& solid, const Candidate& c) {
  if (cols.empty()) return false;
  const Eigen::Vector3f n = cols.plane.head<3>();
  Rect r;
  float low = std::numeric_limits<float>::max();
  for (const Eigen::Vector3f& p : corners(solid, c)) {  // at the grasp pose
    r.add(cols.u.dot(p), cols.v.dot(p));
    low = std::min(low, n.dot(p) + cols.plane[3]);
  }
  const int i0 = std::max(0, int(std::floor((r.lo_u - cols.u0) / cols.cell)));
  const int i1 = std::min(cols.nu - 1, int(std::floor((r.hi_u - cols.u0) / cols.cell)));
  const int j0 = std::max(0, int(std::floor((r.lo_v - cols.v0) / cols.cell)));
  const int j1 = std::min(cols.nv - 1, int(std::floor((r.hi_v - cols.v0) / cols.cell)));
  const BoxFrame f(solid, c, n);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const std::size_t cell = std::size_t(j) * std::size_t(cols.nu) + std::size_t(i);
      for (std::uint32_t k = cols.start[cell]; k < cols.start[cell + 1]; ++k)
        // A column reaches the solid's heights only from a point above its lowest corner.
        if (cols.height[k] >= low && segment_hits(cols, f, solid.half, cols.points[k], cols.height[k]))
          return true;
    }
  return false;
}

bool cuts_column_brute(const Columns& cols, const Solid& solid, const Candidate& c) {
  const BoxFrame f(solid, c, cols.plane.head<3>());
  for (std::size_t k = 0; k < cols.points.size(); ++k)
    if (segment_hits(cols, f, solid.half, cols.points[k], cols.height[k])) return true;
  return false;
}

}  // namespace uwgrasp::grasp
