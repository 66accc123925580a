// Points moved along their rays onto their windows' planes (organised.hpp, move_onto_planes).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/organised_window.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

using namespace window_detail;

namespace {
// A ray meeting the plane within 15 degrees of grazing moves a long way for a small error in the
// plane (1 / sin of the angle): such points stay where they are.
constexpr float kMinIncidence = 0.2588f;  // sin 15 degrees
// The most a point moves, in continuity allowances of one pixel step (depth_change x range):
// farther, the window's plane is not its surface (a thin part, a crease the window straddles).
constexpr float kMaxMove = 3.0f;

// Where point p's ray meets the plane through its window's centroid c with its normal n, as
// the signed move along the ray; NaN when it stays.
float move_along_ray(const Eigen::Vector3f& p, const Eigen::Vector3f& c, const Eigen::Vector3f& n,
                     const Eigen::Vector3f& ray, float limit) {
  if (!n.allFinite()) return std::numeric_limits<float>::quiet_NaN();  // under 3 pixels
  const float along = n.dot(ray);
  if (std::abs(along) < kMinIncidence) return std::numeric_limits<float>::quiet_NaN();
  // The plane n.(x - c) = 0 and the ray p + t ray: t = n.(c - p) / n.ray.
  const float t = n.dot(c - p) / along;
  return std::abs(t) <= limit ? t : std::numeric_limits<float>::quiet_NaN();
}
}  // namespace

double move_onto_planes(Cloud& cloud, std::span<const Eigen::Vector3f> centroids,
                        const OrganisedConfig& cfg, WindowScratch& scratch) {
  if (centroids.size() != cloud.size() || cloud.normals.size() != cloud.size())
    throw Error("move_onto_planes: the centroids or the normals do not fit this cloud");
  const std::span<const float> range = ranges(cloud.points, cloud.viewpoint, scratch.range);
  std::vector<float>& move = scratch.move;  // each point's move along its ray, NaN: none
  move.resize(cloud.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 4096), [&](const auto& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const Eigen::Vector3f ray = (cloud.points[j] - cloud.viewpoint) / std::max(range[j], 1e-6f);
      move[j] = move_along_ray(cloud.points[j], centroids[j], cloud.normals[j], ray,
                               kMaxMove * cfg.depth_change * range[j]);
    }
  });
  // Every move from the points as they were, then applied: no point's plane saw a moved one.
  // The moves' sizes over range^2 measure the noise they took out as a depth camera's law.
  std::vector<float>& size = scratch.sample;
  size.clear();
  for (std::size_t j = 0; j < cloud.size(); ++j) {
    if (std::isnan(move[j])) continue;
    const float r = std::max(range[j], 1e-6f);
    cloud.points[j] += move[j] / r * (cloud.points[j] - cloud.viewpoint);
    size.push_back(std::abs(move[j]) / (r * r));
  }
  if (size.empty()) return 0.0;
  const auto mid = size.begin() + std::ptrdiff_t(size.size() / 2);
  std::nth_element(size.begin(), mid, size.end());
  return 1.4826 * double(*mid);  // a normal deviate's median |x| is 0.6745 sigma
}

}  // namespace uwgrasp::cloud
