#pragma once
// Poses and frames (ARCHITECTURE.md "Frames and units"). Quaternions inside; roll-pitch-yaw
// (ZYX, thesis eq. 2.2-2.4: R = Rz(psi) Ry(theta) Rx(phi)) only at interfaces.
#include <Eigen/Geometry>

namespace uwgrasp {

using Pose = Eigen::Isometry3d;

// R = Rz(yaw) * Ry(pitch) * Rx(roll), eq. 2.2-2.4.
Eigen::Quaterniond quat_from_rpy(double roll, double pitch, double yaw);
Eigen::Quaterniond quat_from_rpy(const Eigen::Vector3d& rpy);
// Inverse of quat_from_rpy with pitch in [-pi/2, pi/2]; at gimbal lock (|pitch| = pi/2) roll is
// set to 0 and the whole rotation about z goes to yaw.
Eigen::Vector3d rpy_from_quat(const Eigen::Quaterniond& q);
Eigen::Vector3d rpy_from_matrix(const Eigen::Matrix3d& R);

Pose make_pose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q);

// Body frame B (x forward, y starboard, z down) from camera optical frame C (x right, y down,
// z forward) for a camera looking straight ahead: x_B = z_C, y_B = x_C, z_B = y_C.
Eigen::Matrix3d body_from_optical();

// A rigid mount on the vehicle: position in B (m) and roll/pitch/yaw (rad, ZYX, eq. 2.2-2.4).
struct Mount {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
};
Pose mount_pose(const Mount& m);
// T_BC for a camera mount: the mount's rotation followed by the optical axes (z forward, x right,
// y down); all-zero rpy is a camera looking straight ahead.
Pose body_from_camera(const Mount& m);

// T_LB: level frame from body frame for the vehicle's roll and pitch at capture.
Pose level_from_body(double roll, double pitch);

// Rodrigues' rotation (eq. 2.5) as a quaternion (eq. 2.6).
Eigen::Quaterniond quat_from_axis_angle(const Eigen::Vector3d& axis, double angle);

}  // namespace uwgrasp
