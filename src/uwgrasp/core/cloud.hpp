#pragma once
// Cloud: one vector per attribute; an empty vector means the attribute is absent.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace uwgrasp {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

struct Cloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;
  std::vector<float> curvature;
  std::vector<Rgb8> colors;
  std::vector<std::uint32_t> labels;
  // Organised clouds (one point per pixel, row-major) have height > 1; unorganised: height 1.
  std::uint32_t width = 0;
  std::uint32_t height = 1;
  // Sensor origin in the cloud's frame (the camera optical frame for sensor clouds).
  Eigen::Vector3f viewpoint = Eigen::Vector3f::Zero();
  // Sensor orientation in the cloud's frame: with `viewpoint`, the camera pose T_FC (a PCD's
  // VIEWPOINT). Identity for a cloud in the camera optical frame.
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool organised() const { return height > 1; }
  bool has_normals() const { return !normals.empty(); }
  bool has_curvature() const { return !curvature.empty(); }
  bool has_colors() const { return !colors.empty(); }
  bool has_labels() const { return !labels.empty(); }
};

// Throws Error naming `what` if an attribute vector is neither empty nor the size of points, or
// width*height disagrees with the point count.
void check_consistent(const Cloud& cloud, const char* what);

// Subset in the order of `indices`; the result is unorganised and keeps the viewpoint.
Cloud select(const Cloud& cloud, std::span<const std::uint32_t> indices);
// The same into `out` (not `cloud` itself), reusing its buffers' capacity.
void select(const Cloud& cloud, std::span<const std::uint32_t> indices, Cloud& out);

// The cloud in another frame: T maps this cloud's frame F to the new one (points, normals,
// viewpoint and orientation move; NaN points stay NaN, so an organised cloud stays organised).
Cloud transformed(const Cloud& cloud, const Eigen::Isometry3d& T);

// The sensor pose in the cloud's frame, T_FC, from viewpoint and orientation.
Eigen::Isometry3d sensor_pose(const Cloud& cloud);

// The finite points, and those at z <= 0: behind a camera at the origin looking along +z. A
// cloud in a camera's optical frame has none behind.
struct BehindCount {
  std::size_t finite = 0, behind = 0;
  double share() const { return finite ? double(behind) / double(finite) : 0.0; }
};
BehindCount behind_camera(const Cloud& cloud);

// Marks the cloud unorganised (width = size, height = 1).
void make_unorganised(Cloud& cloud);

// Centroid of the points (eq. 4.5) and their covariance about it (eq. 4.4, divided by N).
Eigen::Vector3d centroid(const Cloud& cloud);
Eigen::Matrix3d covariance(const Cloud& cloud, const Eigen::Vector3d& mean);

// The same for the subset `indices` of `points`, in double precision, two passes about the
// centroid (stable for small, distant patches). Both are zero for an empty subset.
struct MeanCovariance {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
};
MeanCovariance mean_covariance(std::span<const Eigen::Vector3f> points,
                               std::span<const std::uint32_t> indices);

// Inline and branch-free (& not &&), so that loops over points vectorise: every filter and
// index calls it once per point.
inline bool is_finite(const Eigen::Vector3f& p) {
  constexpr float kMax = std::numeric_limits<float>::max();
  return (std::abs(p.x()) <= kMax) & (std::abs(p.y()) <= kMax) & (std::abs(p.z()) <= kMax);
}

}  // namespace uwgrasp
