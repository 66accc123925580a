#include "uwgrasp/grasp/metrics.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::grasp {

double alignment(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double n = a.norm() * b.norm();
  if (!(n > 0.0)) return 0.0;
  return std::min(1.0, std::abs(a.dot(b)) / n);
}

double orientation_term(double angle, OrientationForm form) {
  const double pi = std::numbers::pi;
  const double a = std::remainder(angle, 2.0 * pi);  // (-pi, pi]
  if (form == OrientationForm::monotone && std::abs(a) > pi / 2) return 0.0;
  return 1.0 - std::abs(std::sin(a));
}

double orientation_score(const Eigen::Vector3d& rpy, const OrientationConfig& cfg) {
  const double sum = cfg.roll + cfg.pitch + cfg.yaw;
  if (!(sum > 0.0) || cfg.roll < 0 || cfg.pitch < 0 || cfg.yaw < 0)
    throw Error("grasp.score.orientation weights must be >= 0 and not all 0");
  return (cfg.roll * orientation_term(rpy.x(), cfg.form) +
          cfg.pitch * orientation_term(rpy.y(), cfg.form) +
          cfg.yaw * orientation_term(rpy.z(), cfg.form)) /
         sum;
}

ContactScores contact_scores(const Eigen::Vector3d& left, const Eigen::Vector3d& right,
                             const Eigen::Vector3d& left_normal,
                             const Eigen::Vector3d& right_normal, const Eigen::Vector3d& closing,
                             double min_separation) {
  ContactScores s;
  const Eigen::Vector3d d = right - left;
  s.line = d.norm() >= min_separation ? d.normalized() : closing.normalized();
  s.left = alignment(s.line, left_normal);
  s.right = alignment(s.line, right_normal);
  return s;
}

Antipodal antipodal(const ContactScores& c, double mu) {
  // cos of the angle between the line and each normal is the contact score itself.
  const double worst = std::min(c.left, c.right);
  Antipodal a;
  if (worst <= 0.0) {
    a.mu_required = std::numeric_limits<double>::infinity();
  } else {
    const double angle = std::acos(std::min(1.0, worst));
    a.mu_required = std::tan(angle);
  }
  a.ok = a.mu_required <= mu;
  return a;
}

double inlier_score(std::size_t inliers, double max_inliers) {
  if (!(max_inliers > 0.0)) throw Error("maximum inliers must be positive");
  return std::min(1.0, double(inliers) / max_inliers);
}

double max_inliers_volume(const Eigen::Vector3f& size, double leaf) {
  if (!(leaf > 0.0)) throw Error("derived maximum inliers need a positive voxel size");
  return std::max(1.0, std::floor(double(size.prod()) / (leaf * leaf * leaf)));
}

double max_inliers_surface(const Eigen::Vector3f& size, double leaf) {
  if (!(leaf > 0.0)) throw Error("derived maximum inliers need a positive voxel size");
  // Largest planar section of a box: its largest face or a diagonal section through it.
  const double x = size.x(), y = size.y(), z = size.z();
  const double section = std::max({x * y, y * z, x * z, x * std::hypot(y, z), y * std::hypot(x, z),
                                   z * std::hypot(x, y)});
  return std::max(1.0, std::floor(section / (leaf * leaf)));
}

double total_score(const Scores& s, const Weights& w) {
  return w.normal * s.normal + w.orientation * s.orientation +
         w.contact * (s.contact_left + s.contact_right) + w.inliers * s.inliers +
         w.vehicle * s.vehicle;
}

void check_weights(const Weights& w) {
  for (double v : {w.normal, w.orientation, w.contact, w.inliers, w.vehicle})
    if (!std::isfinite(v) || v < 0.0)
      throw Error("grasp.score.weights must be finite and >= 0, got " + std::to_string(v));
  if (w.normal + w.orientation + w.contact + w.inliers + w.vehicle <= 0.0)
    throw Error("grasp.score.weights sum to 0: no grasp could be ranked");
}

double force_closure_mu(const Eigen::Vector3d& c_left, const Eigen::Vector3d& n_left,
                        const Eigen::Vector3d& c_right, const Eigen::Vector3d& n_right,
                        const Eigen::Vector3d& closing) {
  Eigen::Vector3d line = c_right - c_left;
  line = line.norm() > 1e-6 ? line.normalized() : closing.normalized();
  // Each finger pushes along the line into the object, against the outward normal there.
  const auto angle = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
  };
  const double worst = std::max(angle(line, -n_left.normalized()), angle(-line, -n_right.normalized()));
  if (!(worst < 0.5 * std::numbers::pi - 1e-12)) return std::numeric_limits<double>::infinity();
  return std::tan(worst);
}

}  // namespace uwgrasp::grasp
