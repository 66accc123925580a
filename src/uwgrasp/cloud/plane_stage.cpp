#include "uwgrasp/cloud/plane_stage.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_set>

namespace uwgrasp::cloud {

// The plane's inliers again, within max(distance, noise_sigmas x sigma(range)) of it: the noise
// is measured twice, the second time in a band wide enough for the first estimate's spread.
void widen_to_noise(const Cloud& cur, const PlaneConfig& cfg, Preprocessed& out) {
  const Eigen::Vector4f& n = out.plane.coefficients;
  float band = std::max(3.0f * cfg.distance, 0.02f);
  out.noise = plane_noise(cur, n, band);
  if (!out.noise.found) return;
  float widest = 0.0f;
  for (const auto i : out.plane.inliers)
    widest = std::max(widest, float(out.noise.at((cur.points[i] - cur.viewpoint).norm())));
  if (5.0f * widest > band) out.noise = plane_noise(cur, n, 5.0f * widest);
  if (!out.noise.found) return;
  out.plane.inliers.clear();
  for (std::size_t i = 0; i < cur.size(); ++i) {
    const Eigen::Vector3f& p = cur.points[i];
    const double limit =
        std::max(double(cfg.distance), cfg.noise_sigmas * out.noise.at((p - cur.viewpoint).norm()));
    if (std::abs(n.head<3>().dot(p) + n[3]) <= limit) out.plane.inliers.push_back(std::uint32_t(i));
  }
}

// Of the widened band's points beyond the fixed tolerance, those whose window normal turns more
// than normal_angle from the plane's leave the inliers (4.1.4 with the normals, as PCL's
// organised plane segmentation also tests them).
void keep_turned_points(const Cloud& cur, const PixelMap& map, const PreprocessConfig& cfg,
                        PlaneResult& plane) {
  const Eigen::Vector4f& n = plane.coefficients;
  std::vector<std::uint32_t> band;
  for (const auto i : plane.inliers)
    if (std::abs(n.head<3>().dot(cur.points[i]) + n[3]) > cfg.plane.distance) band.push_back(i);
  if (band.empty()) return;
  const auto normals = window_normals_of(cur.points, map, cfg.organised, cur.viewpoint, band);
  const float cos_max = std::cos(cfg.plane.normal_angle * float(std::numbers::pi) / 180.0f);
  std::vector<char> off(cur.size(), 0);
  for (std::size_t b = 0; b < band.size(); ++b)
    off[band[b]] = std::abs(normals[b].normal.dot(n.head<3>())) < cos_max;
  std::erase_if(plane.inliers, [&](std::uint32_t i) { return off[i] != 0; });
}

// Whether the points clearly off the plane (beyond three inlier distances) and over its inliers
// (their projection along the normal within a cell of an inlier's) lie mostly on the sensor's
// side of it, as objects standing on a support do, rather than behind it, as the rest of an
// object does behind one of its own faces. Points beyond the plane's edge (the room behind a
// table) do not count either way.
bool supports_the_rest(const Cloud& cur, const PlaneConfig& cfg, const PlaneResult& plane) {
  const Eigen::Vector4f& n = plane.coefficients;
  const Eigen::Vector3f normal = n.head<3>();
  const Eigen::Vector3f a = normal.unitOrthogonal(), b = normal.cross(a);
  const float cell = std::max(2.0f * cfg.distance, 0.01f);
  const auto key = [&](const Eigen::Vector3f& p, int du, int dv) {
    const auto u = std::int64_t(std::floor(a.dot(p) / cell)) + du,
               v = std::int64_t(std::floor(b.dot(p) / cell)) + dv;
    return (u << 32) ^ (v & 0xffffffff);
  };
  std::unordered_set<std::int64_t> over;
  for (const auto i : plane.inliers) over.insert(key(cur.points[i], 0, 0));
  const float sensor = normal.dot(cur.viewpoint) + n[3];
  std::size_t front = 0, behind = 0;
  for (const auto& p : cur.points) {
    const float d = normal.dot(p) + n[3];
    if (std::abs(d) <= 3.0f * cfg.distance) continue;
    bool inside = false;
    for (int du = -1; du <= 1 && !inside; ++du)
      for (int dv = -1; dv <= 1 && !inside; ++dv) inside = over.count(key(p, du, dv)) > 0;
    if (inside) ++(d * sensor > 0.0f ? front : behind);
  }
  return front >= behind;
}

}  // namespace uwgrasp::cloud
