#include "uwgrasp/grasp/sight.hpp"

#include <tbb/parallel_for.h>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::grasp {

namespace {
using V3 = Eigen::Vector3f;
using sight_detail::bin_of;
using sight_detail::kInf;

SurfaceCells make_surface_cells(std::span<const V3> object, float cell) {
  SurfaceCells s;
  if (object.empty()) return s;
  V3 lo = V3::Constant(std::numeric_limits<float>::max()), hi = -lo;
  for (const V3& p : object) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  s.cell = cell;
  const auto dims = [&] { return ((hi - lo) / s.cell).array().floor().cast<int>() + 3; };
  while (double(dims().prod()) > 4e6) s.cell *= 1.25f;
  const Eigen::Array3i n = dims();
  s.nx = n.x(), s.ny = n.y(), s.nz = n.z();
  s.origin = lo - V3::Constant(s.cell);  // one empty cell of margin for the dilation
  s.marked.assign(std::size_t(n.prod()), 0);
  for (const V3& p : object) {
    // Clamped: (p - origin) / cell may round past the last inner cell.
    const V3 q = (p - s.origin) / s.cell;
    const int i = std::clamp(int(q.x()), 1, s.nx - 2), j = std::clamp(int(q.y()), 1, s.ny - 2),
              k = std::clamp(int(q.z()), 1, s.nz - 2);
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          s.marked[(std::size_t(k + dk) * std::size_t(s.ny) + std::size_t(j + dj)) * std::size_t(s.nx) +
                   std::size_t(i + di)] = 1;
  }
  return s;
}

// The view's map from the bins' nearest depths (`seen`, width x height from u0, v0): an empty
// bin takes the nearest of the 3 x 3 around it, once here rather than at every lookup (the
// symmetry search looks up millions a frame, many over the removed seafloor, where every bin is
// empty), and the map grows by a bin on each side for the bins next to it.
void fill_gaps(SceneView& view, const std::vector<float>& seen) {
  const int w = view.width, h = view.height;
  const auto at = [&](int u, int v) {
    return u < 0 || v < 0 || u >= w || v >= h
               ? kInf
               : seen[std::size_t(v) * std::size_t(w) + std::size_t(u)];
  };
  view.u0 -= 1, view.v0 -= 1, view.width = w + 2, view.height = h + 2;
  view.near.assign(std::size_t(view.width) * std::size_t(view.height), kInf);
  tbb::parallel_for(-1, h + 1, [&](int v) {  // rows in parallel, each writing its own
    for (int u = -1; u <= w; ++u) {
      float d = at(u, v);
      if (!(d < kInf))
        for (int dv = -1; dv <= 1; ++dv)
          for (int du = -1; du <= 1; ++du) d = std::min(d, at(u + du, v + dv));
      view.near[std::size_t(v + 1) * std::size_t(view.width) + std::size_t(u + 1)] = d;
    }
  });
}
}  // namespace

SceneView make_scene_view(std::span<const Eigen::Vector3f> scene, const std::optional<Eigen::Vector4f>& floor,
                          const Pose& camera_from_level, float resolution,
                          std::span<const Eigen::Vector3f> object, float cell) {
  if (!(resolution > 0.0f)) throw Error("grasp.shape.resolution must be positive");
  if (!(cell > 0.0f)) throw Error("grasp.shape.symmetry.tolerance must be positive");
  SceneView view;
  view.resolution = resolution, view.floor = floor, view.camera_from_level = camera_from_level;
  view.surface = make_surface_cells(object, cell);
  const float inverse = 1.0f / resolution;
  int u1 = std::numeric_limits<int>::min(), v1 = u1;
  view.u0 = view.v0 = std::numeric_limits<int>::max();
  for (const V3& p : scene) {
    if (!(p.z() > 0.0f)) continue;
    const int u = bin_of(p.x() / p.z(), inverse), v = bin_of(p.y() / p.z(), inverse);
    view.u0 = std::min(view.u0, u), view.v0 = std::min(view.v0, v), u1 = std::max(u1, u), v1 = std::max(v1, v);
  }
  // Nothing in front of the camera: an empty map, placed at 0 (from the sentinels, a lookup's
  // bin minus u0 would overflow).
  if (u1 < view.u0) {
    view.u0 = view.v0 = 0;
    return view;
  }
  view.width = u1 - view.u0 + 1, view.height = v1 - view.v0 + 1;
  if (double(view.width) * double(view.height) > 5e7)
    throw Error("grasp.shape.resolution is too fine for this scene's field of view");
  std::vector<float> seen(std::size_t(view.width) * std::size_t(view.height), kInf);
  for (const V3& p : scene) {
    if (!(p.z() > 0.0f)) continue;
    const std::size_t k = std::size_t(bin_of(p.y() / p.z(), inverse) - view.v0) * std::size_t(view.width) +
                          std::size_t(bin_of(p.x() / p.z(), inverse) - view.u0);
    seen[k] = std::min(seen[k], p.z());
  }
  fill_gaps(view, seen);
  return view;
}

Seen classify(const SceneView& view, const Eigen::Vector3f& p_level, float tolerance) {
  return classify_camera(view, (view.camera_from_level * p_level.cast<double>()).cast<float>(), p_level,
                         tolerance);
}

}  // namespace uwgrasp::grasp
