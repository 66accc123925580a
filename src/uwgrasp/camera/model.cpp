#include "uwgrasp/camera/model.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::camera {

Eigen::Vector2d Pinhole::distort(const Eigen::Vector2d& xy) const {
  const auto& [k1, k2, p1, p2, k3] = distortion;
  const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

bool Pinhole::distorted() const {
  for (const double d : distortion)
    if (d != 0.0) return true;
  return false;
}

Eigen::Vector2d Pinhole::project(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d d = distort(Eigen::Vector2d(p.x() / p.z(), p.y() / p.z()));
  return {fx * d.x() + cx, fy * d.y() + cy};
}

Eigen::Vector3d Pinhole::unproject(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector2d target((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
  Eigen::Vector2d xy = target;
  if (distorted()) {
    // x = x_d - (distort(x) - x): converges for the distortions lenses have (OpenCV's scheme).
    for (int i = 0; i < 100; ++i) {
      const Eigen::Vector2d next = xy + (target - distort(xy));
      const bool done = (next - xy).norm() < 1e-13;
      xy = next;
      if (done) break;
    }
  }
  return {xy.x(), xy.y(), 1.0};
}

void check(const Pinhole& c, const std::string& what) {
  const auto fail = [&](const std::string& field, const std::string& why) {
    throw Error(what + ": " + field + " " + why);
  };
  if (c.width < 8 || c.height < 8) fail("image size", "must be at least 8 x 8 pixels");
  if (!(std::isfinite(c.fx) && c.fx > 0.0) || !(std::isfinite(c.fy) && c.fy > 0.0))
    fail("K", "must have positive, finite focal lengths fx and fy (the matrix is singular)");
  if (!std::isfinite(c.cx) || !std::isfinite(c.cy) || c.cx < -0.5 || c.cy < -0.5 ||
      c.cx > c.width || c.cy > c.height)
    fail("K", "has its principal point outside the image");
  for (const double d : c.distortion)
    if (!std::isfinite(d)) fail("D", "must be finite");
}

void check(const StereoRig& s, const std::string& what) {
  check(s.left, what + " (left camera)");
  check(s.right, what + " (right camera)");
  if (!s.R.allFinite() ||
      (s.R.transpose() * s.R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
      std::abs(s.R.determinant() - 1.0) > 1e-6)
    throw Error(what + ": R is not a rotation");
  if (!s.T.allFinite() || !(s.T.norm() > 0.0))
    throw Error(what + ": T must be a finite, non-zero baseline");
}

}  // namespace uwgrasp::camera
