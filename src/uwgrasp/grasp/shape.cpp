#include "uwgrasp/grasp/shape.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/grasp/occlusion.hpp"
#include "uwgrasp/grasp/shape_shell.hpp"

namespace uwgrasp::grasp {

namespace {
using namespace shape_detail;

// The seafloor's depth (L's z) under (x, y), or nullopt where the plane is too steep to rest on.
std::optional<float> floor_z(const std::optional<FloorPlane>& f, float x, float y) {
  if (!f || std::abs((*f)[2]) < 0.3f) return std::nullopt;
  return -((*f)[0] * x + (*f)[1] * y + (*f)[3]) / (*f)[2];
}

// The seafloor's down in L: the way the symmetry search takes as down. Objects rest on the
// seafloor, so on a sloping one their symmetry planes are square to it, not to gravity (judged,
// 20 degrees of slope: the lying bottle held 60 of 140 top-1s with gravity's down). L's own down
// without a floor, for one within kLevelEnough of level (the search's own tilt steps cover that;
// level seafloors keep their planes bit for bit) or one steeper than kMaxFloorTilt (a wall).
V3 seafloor_down(const std::optional<FloorPlane>& floor) {
  constexpr float kLevelEnough = 0.035f;  // rad, 2 degrees
  if (!floor) return V3::UnitZ();
  const V3 n = floor->head<3>().normalized(), up = -V3::UnitZ();
  const float tilt = std::acos(std::clamp(n.dot(up), -1.0f, 1.0f));
  if (!(tilt > kLevelEnough) || tilt > float(kMaxFloorTilt)) return V3::UnitZ();
  return -n;
}

// Sizes the grid over the object and its mirrored back, down to the seafloor below it (or its
// lowest point).
void size_grid(ObjectShape& s, std::span<const V3> level, std::span<const V3> mirrored,
               const std::optional<FloorPlane>& floor, const ShapeConfig& cfg) {
  V3 lo = V3::Constant(std::numeric_limits<float>::max()), hi = -lo;
  for (const V3& p : level) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  for (const V3& p : mirrored) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const float pad = cfg.min_thickness;
  lo.head<2>() -= V3::Constant(pad).head<2>(), hi.head<2>() += V3::Constant(pad).head<2>();
  float bottom = hi.z() + pad;
  for (const float x : {lo.x(), hi.x()})
    for (const float y : {lo.y(), hi.y()})
      if (const auto z = floor_z(floor, x, y)) bottom = std::max(bottom, std::min(*z, hi.z() + 2.0f * (hi - lo).maxCoeff()));
  hi.z() = bottom;
  s.voxel = cfg.voxel;
  const auto dims = [&] { return ((hi - lo) / s.voxel).array().ceil().cast<int>() + 1; };
  while (double(dims().prod()) > double(cfg.max_voxels)) s.voxel *= 1.25f;
  const Eigen::Array3i n = dims();
  s.nx = n.x(), s.ny = n.y(), s.nz = n.z();
  s.origin = lo;
  s.cells.assign(std::size_t(n.prod()), Occupancy::free);
}

// Marks the seen voxels, then the mirrored ones still free (keeping one mirrored point per
// voxel), and returns per column the highest of them.
std::vector<int> mark_surfaces(Grid g, std::span<const V3> level, std::span<const V3> mirrored,
                               std::span<const V3> mirrored_normals) {
  ObjectShape& s = g.s;
  std::vector<int> top(std::size_t(s.nx) * std::size_t(s.ny), s.nz);
  const auto mark = [&](const V3& p, Occupancy o) {
    const Eigen::Vector3i c = g.cell(p);
    if (!g.inside(c.x(), c.y(), c.z())) return false;
    Occupancy& cell = s.cells[g.index(c.x(), c.y(), c.z())];
    if (o == Occupancy::mirrored && cell != Occupancy::free) return false;
    cell = o;
    for (int dj = -1; dj <= 1; ++dj)  // dilated by one column: gaps between points are not holes
      for (int di = -1; di <= 1; ++di)
        if (g.inside(c.x() + di, c.y() + dj, 0)) {
          int& t = top[std::size_t(c.y() + dj) * std::size_t(s.nx) + std::size_t(c.x() + di)];
          t = std::min(t, c.z());
        }
    return true;
  };
  for (const V3& p : level) mark(p, Occupancy::seen);
  s.mirrored_points.reserve(mirrored.size()), s.mirrored_normals.reserve(mirrored.size());
  for (std::size_t i = 0; i < mirrored.size(); ++i)
    if (mark(mirrored[i], Occupancy::mirrored))
      s.mirrored_points.push_back(mirrored[i]), s.mirrored_normals.push_back(mirrored_normals[i]);
  return top;
}

// Marks the unseen voxels under the visible (and mirrored) surface down to the seafloor, and
// within the minimum thickness behind each visible point, wherever the camera's view is
// blocked by the object.
template <class Shadow>
void fill_unseen(Grid g, std::span<const V3> camera, const std::vector<int>& top, const Frames& frames,
                 const std::optional<FloorPlane>& floor, const ShapeConfig& cfg, Shadow in_shadow) {
  ObjectShape& s = g.s;
  // Columns in parallel: each writes its own cells.
  tbb::parallel_for(0, s.ny, [&](int j) {
    for (int i = 0; i < s.nx; ++i) {
      const V3 base = g.centre(i, j, 0);
      const auto fz = floor_z(floor, base.x(), base.y());
      const int last = fz ? std::min(s.nz - 1, int(std::floor((*fz - cfg.floor_clearance - s.origin.z()) / s.voxel)))
                          : s.nz - 1;
      for (int k = top[std::size_t(j) * std::size_t(s.nx) + std::size_t(i)] + 1; k <= last; ++k)
        if (s.cells[g.index(i, j, k)] == Occupancy::free && in_shadow(g.centre(i, j, k)))
          s.cells[g.index(i, j, k)] = Occupancy::assumed;
    }
  });
  // The visible points in parallel (serially 2.7-7 ms on real frames): a cell only ever turns
  // from free or assumed to thin here, so which cells end thin does not depend on the order in
  // which points reach them. Two points may reach one cell: it is read and written atomically.
  const int steps = int(std::ceil(cfg.min_thickness / s.voxel));
  tbb::parallel_for(std::size_t(0), camera.size(), [&](std::size_t n) {
    const V3& c = camera[n];
    const V3 u = c.normalized();
    for (int t = 1; t <= steps; ++t) {
      const V3 p = (frames.level_from_camera * (c + u * (float(t) * s.voxel)).cast<double>()).cast<float>();
      const Eigen::Vector3i q = g.cell(p);
      if (!g.inside(q.x(), q.y(), q.z())) continue;
      std::atomic_ref<Occupancy> cell(s.cells[g.index(q.x(), q.y(), q.z())]);
      const Occupancy o = cell.load(std::memory_order_relaxed);
      if ((o == Occupancy::free || o == Occupancy::assumed) && in_shadow(p))
        cell.store(Occupancy::thin, std::memory_order_relaxed);
    }
  });
}

}  // namespace

std::size_t ObjectShape::count(Occupancy o) const { return std::size_t(std::count(cells.begin(), cells.end(), o)); }

float sensor_noise(std::span<const Eigen::Vector3f> camera, float depth_error) {
  if (!(depth_error > 0.0f) || camera.empty()) return 0.0f;
  // The median depth of the object's points (a sample of them: the median of a few thousand is
  // as good); the error grows with depth^2 (eq. 3.25 differentiated).
  const std::size_t step = std::max<std::size_t>(1, camera.size() / 2048);
  std::vector<float> z;
  z.reserve(camera.size() / step + 1);
  for (std::size_t i = 0; i < camera.size(); i += step) z.push_back(camera[i].z());
  std::nth_element(z.begin(), z.begin() + std::ptrdiff_t(z.size() / 2), z.end());
  const float depth = std::max(0.0f, z[z.size() / 2]);
  return depth_error * depth * depth;
}

ObjectShape complete_shape(std::span<const Eigen::Vector3f> level,
                           std::span<const Eigen::Vector3f> camera, const Frames& frames,
                           const std::optional<FloorPlane>& floor, const ShapeConfig& cfg,
                           std::span<const Eigen::Vector3f> normals, const SceneSight* scene,
                           ShapeTrees trees) {
  if (level.empty() || level.size() != camera.size())
    throw Error("object shape: the object has no points (or the level and camera points differ)");
  if (!(cfg.voxel > 0.0f) || !(cfg.resolution > 0.0f))
    throw Error("grasp.shape.voxel and grasp.shape.resolution must be positive");
  if (!(cfg.min_thickness >= 0.0f) || !(cfg.shadow_tolerance >= 0.0f) || !(cfg.floor_clearance >= 0.0f))
    throw Error("grasp.shape: min_thickness, shadow_tolerance and floor_clearance must be >= 0");
  ObjectShape s;
  s.measured_noise = surface_noise(camera, 12, 1500, trees.camera);
  s.sensor_noise = sensor_noise(camera, cfg.depth_error);
  s.noise = std::max(s.measured_noise, s.sensor_noise);
  const Pose camera_from_level = frames.level_from_camera.inverse();
  std::vector<V3> mirrored, mirrored_normals;
  if (scene != nullptr && cfg.symmetry.enabled) {
    const float tolerance = cfg.symmetry.tolerance + cfg.symmetry.noise_sigmas * s.noise;
    const SceneView view = make_scene_view(scene->points, scene->floor, camera_from_level, cfg.resolution, level,
                                           0.5f * tolerance);
    s.planes = find_symmetry(level, view, s.noise, cfg.symmetry, trees.level, seafloor_down(floor));
    mirror_points(level, normals, s.planes, view, tolerance, mirrored, mirrored_normals);
  }
  size_grid(s, level, mirrored, floor, cfg);
  const DepthMap map = make_depth_map(camera, cfg.resolution);
  const float tolerance = cfg.shadow_tolerance + 2.0f * s.noise;
  const auto in_shadow = [&](const V3& p) {
    const V3 c = (camera_from_level * p.cast<double>()).cast<float>();
    return c.z() > 0.0f && map.at(c.x() / c.z(), c.y() / c.z()) < c.z() - tolerance;
  };
  const std::vector<int> top = mark_surfaces(Grid{s}, level, mirrored, mirrored_normals);
  fill_unseen(Grid{s}, camera, top, frames, floor, cfg, in_shadow);
  const auto any = [](Occupancy) { return true; };
  const auto is_free = [](Occupancy o) { return o == Occupancy::free; };
  shell(Grid{s}, any, is_free, true, s.points, s.normals);
  const auto is_thin = [](Occupancy o) { return o == Occupancy::thin; };
  const auto beyond_core = [](Occupancy o) {
    return o == Occupancy::free || o == Occupancy::assumed || o == Occupancy::mirrored;
  };
  shell(Grid{s}, is_thin, beyond_core, false, s.core_points, s.core_normals);
  return s;
}

}  // namespace uwgrasp::grasp
