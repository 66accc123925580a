#pragma once
// What one view saw, for judging where a hypothesised point would stand (symmetry.hpp): in front
// of what the camera saw along its ray (free space it saw through) or under the seafloor; on the
// object's seen surface; or hidden behind what was seen, or never observed.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "uwgrasp/core/pose.hpp"

namespace uwgrasp::grasp {

// The object's seen surface as cells of a grid in L, each marked when a seen point lies in it
// or in a neighbouring cell: a point is on the seen surface when its cell is marked.
struct SurfaceCells {
  Eigen::Vector3f origin = Eigen::Vector3f::Zero();  // corner of cell (0, 0, 0)
  float cell = 0.0f;
  int nx = 0, ny = 0, nz = 0;
  std::vector<std::uint8_t> marked;  // x fastest
  // Inline: the symmetry search asks it millions of times a frame (classify_camera).
  bool contains(const Eigen::Vector3f& p) const {
    if (marked.empty()) return false;
    const Eigen::Vector3f q = (p - origin) / cell;
    // floor(q) lies in [0, n) exactly when q does, and there truncation is floor (NaN: outside).
    if (!(q.x() >= 0.0f && q.y() >= 0.0f && q.z() >= 0.0f && q.x() < float(nx) &&
          q.y() < float(ny) && q.z() < float(nz)))
      return false;
    return marked[(std::size_t(q.z()) * std::size_t(ny) + std::size_t(q.y())) * std::size_t(nx) +
                  std::size_t(q.x())] != 0;
  }
};

// What the camera saw: the nearest depth (camera z) of the scene's processed points per bin of
// normalised image coordinates, the seafloor plane (camera frame, n.p + d = 0) where no point
// was seen, and the object's own seen surface.
struct SceneView {
  float resolution = 0.003f;
  int u0 = 0, v0 = 0, width = 0, height = 0;
  // Per bin, the nearest depth seen in it or, in an empty bin, in the 3 x 3 around it (gaps
  // between points are not holes); +inf where nothing was seen there. One bin wider on each side
  // than the bins holding points.
  std::vector<float> near;
  std::optional<Eigen::Vector4f> floor;
  Pose camera_from_level = Pose::Identity();
  SurfaceCells surface;
};

// `scene`: every processed point (camera frame); `object`: the object's seen points (L), marked
// in cells of `cell` m (grown when the object needs more than 4 million). Throws Error for a
// non-positive resolution or cell, or a field of view too large for the resolution.
SceneView make_scene_view(std::span<const Eigen::Vector3f> scene, const std::optional<Eigen::Vector4f>& floor,
                          const Pose& camera_from_level, float resolution,
                          std::span<const Eigen::Vector3f> object, float cell);

// Where a point (L) stands against the view: in front of what the camera saw along its ray, or
// under the seafloor (violation: seen free space); on the object's seen surface (support); or
// anywhere else, hidden behind what was seen or never observed.
enum class Seen : std::uint8_t { violation, support, hidden };
Seen classify(const SceneView& view, const Eigen::Vector3f& p_level, float tolerance);

namespace sight_detail {
inline constexpr float kInf = std::numeric_limits<float>::infinity();

// floor(clamp(v * inverse)) without a floor call (SSE2 has no rounding instruction): truncation,
// then one down where that rounded up; exact, as a float above 2^23 is already whole and an int
// below it converts back exactly.
inline int bin_of(float v, float inverse) {
  const float x = std::clamp(v * inverse, -1e8f, 1e8f);
  const int t = int(x);
  return float(t) > x ? t - 1 : t;
}

// The nearest depth seen along the ray through image point (x, y): the view's in its bin (see
// SceneView::near), else the seafloor's; +inf when nothing was seen there.
inline float seen_depth(const SceneView& view, float x, float y) {
  const float inverse = 1.0f / view.resolution;
  const int u = bin_of(x, inverse) - view.u0, v = bin_of(y, inverse) - view.v0;
  const bool in = u >= 0 && v >= 0 && u < view.width && v < view.height;
  const float d = in ? view.near[std::size_t(v) * std::size_t(view.width) + std::size_t(u)] : kInf;
  if (d < kInf || !view.floor) return d;
  const float den = view.floor->head<3>().dot(Eigen::Vector3f(x, y, 1.0f));
  if (std::abs(den) > 1e-6f && -(*view.floor)[3] / den > 0.0f) return -(*view.floor)[3] / den;
  return kInf;
}
}  // namespace sight_detail

// classify() for a point already in the camera frame (`c`; `p` is the same point in L): the form
// the symmetry search calls millions of times, so it is inline.
inline Seen classify_camera(const SceneView& view, const Eigen::Vector3f& c, const Eigen::Vector3f& p,
                            float tolerance) {
  if (view.floor) {
    // The camera (the origin) is on the side of d's sign; a point past the plane is under it.
    const float side = view.floor->head<3>().dot(c) + (*view.floor)[3];
    if (side * (*view.floor)[3] < 0.0f && std::abs(side) > tolerance) return Seen::violation;
  }
  if (!(c.z() > 1e-3f)) return Seen::violation;
  if (sight_detail::seen_depth(view, c.x() / c.z(), c.y() / c.z()) > c.z() + tolerance) return Seen::violation;
  return view.surface.contains(p) ? Seen::support : Seen::hidden;
}

}  // namespace uwgrasp::grasp
