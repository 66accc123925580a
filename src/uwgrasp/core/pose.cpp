#include "uwgrasp/core/pose.hpp"

#include <algorithm>
#include <cmath>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp {

Eigen::Quaterniond quat_from_rpy(double roll, double pitch, double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
}

Eigen::Quaterniond quat_from_rpy(const Eigen::Vector3d& rpy) {
  return quat_from_rpy(rpy.x(), rpy.y(), rpy.z());
}

Eigen::Vector3d rpy_from_matrix(const Eigen::Matrix3d& R) {
  // R(2,0) = -sin(pitch); clamp against rounding just outside [-1, 1].
  const double s = std::clamp(-R(2, 0), -1.0, 1.0);
  const double pitch = std::asin(s);
  if (std::abs(s) > 1.0 - 1e-12) {
    // Gimbal lock: only yaw -/+ roll is observable; put it all in yaw.
    const double yaw = std::atan2(-R(0, 1), R(1, 1));
    return {0.0, pitch, yaw};
  }
  return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
}

Eigen::Vector3d rpy_from_quat(const Eigen::Quaterniond& q) {
  return rpy_from_matrix(q.normalized().toRotationMatrix());
}

Pose make_pose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  Pose p = Pose::Identity();
  p.linear() = q.normalized().toRotationMatrix();
  p.translation() = t;
  return p;
}

Pose mount_pose(const Mount& m) { return make_pose(m.position, quat_from_rpy(m.rpy)); }

Pose body_from_camera(const Mount& m) {
  Pose T = mount_pose(m);
  T.linear() = T.linear() * body_from_optical();
  return T;
}

Eigen::Matrix3d body_from_optical() {
  Eigen::Matrix3d R;
  // Columns are the optical axes expressed in the body frame.
  R << 0, 0, 1,  //
      1, 0, 0,   //
      0, 1, 0;
  return R;
}

Pose level_from_body(double roll, double pitch) {
  return make_pose(Eigen::Vector3d::Zero(), quat_from_rpy(roll, pitch, 0.0));
}

Eigen::Quaterniond quat_from_axis_angle(const Eigen::Vector3d& axis, double angle) {
  const double n = axis.norm();
  if (!(n > 0.0) || !std::isfinite(n)) throw Error("rotation axis must be a non-zero vector");
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis / n));
}

}  // namespace uwgrasp
