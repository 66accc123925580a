#include "uwgrasp/camera/triangulate.hpp"

#include <Eigen/SVD>
#include <algorithm>

namespace uwgrasp::camera {

Eigen::Vector3d triangulate_dlt(const Projection& P1, const Projection& P2,
                                const Eigen::Vector2d& x1, const Eigen::Vector2d& x2) {
  Eigen::Matrix4d A;  // two rows per view
  A.row(0) = x1.x() * P1.row(2) - P1.row(0);
  A.row(1) = x1.y() * P1.row(2) - P1.row(1);
  A.row(2) = x2.x() * P2.row(2) - P2.row(0);
  A.row(3) = x2.y() * P2.row(2) - P2.row(1);
  // Rows scaled to unit length: the SVD then weighs both views alike (Hartley & Zisserman 12.2).
  for (int i = 0; i < 4; ++i) A.row(i) /= std::max(A.row(i).norm(), 1e-300);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  return X.head<3>() / X.w();
}

StereoRig virtual_rig(const StereoRig& air, const Pinax& left, const Pinax& right) {
  StereoRig v = air;
  v.left = left.virtual_camera, v.right = right.virtual_camera;
  v.T = air.T + left.centre_z * air.R.col(2) - right.centre_z * Eigen::Vector3d::UnitZ();
  return v;
}

Triangulator::Triangulator(const StereoRig& rig, const std::optional<FlatPort>& port,
                           double port_reference)
    : used_(rig) {
  check(rig, "stereo rig");
  if (!port) return;
  left_ = make_pinax(rig.left, *port, port_reference);
  right_ = make_pinax(rig.right, *port, port_reference);
  used_ = virtual_rig(rig, *left_, *right_);
}

namespace {
std::optional<Eigen::Vector3d> ray(const Pinhole& used, const std::optional<Pinax>& pinax,
                                   const Eigen::Vector2d& px) {
  if (!pinax) return used.unproject(px);
  const auto v = virtual_pixel(*pinax, px);
  if (!v) return std::nullopt;
  return used.unproject(*v);
}
}  // namespace

std::optional<Eigen::Vector3d> Triangulator::left_ray(const Eigen::Vector2d& a) const {
  return ray(used_.left, left_, a);
}
std::optional<Eigen::Vector3d> Triangulator::right_ray(const Eigen::Vector2d& b) const {
  return ray(used_.right, right_, b);
}

std::optional<Eigen::Vector3d> Triangulator::point(const Eigen::Vector2d& a,
                                                   const Eigen::Vector2d& b) const {
  const auto xl = left_ray(a), xr = right_ray(b);
  if (!xl || !xr) return std::nullopt;
  Projection P1 = Projection::Zero(), P2;
  P1.leftCols<3>().setIdentity();
  P2 << used_.R, used_.T;
  const Eigen::Vector3d X = triangulate_dlt(P1, P2, xl->head<2>(), xr->head<2>());
  return left_ ? camera_from_virtual(*left_, X) : X;
}

}  // namespace uwgrasp::camera
