#include <gtest/gtest.h>

#include <numbers>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp {

namespace {
// Eq. 2.2-2.4 written out.
Eigen::Matrix3d rzyx(double phi, double theta, double psi) {
  Eigen::Matrix3d rx, ry, rz;
  rx << 1, 0, 0, 0, std::cos(phi), -std::sin(phi), 0, std::sin(phi), std::cos(phi);
  ry << std::cos(theta), 0, std::sin(theta), 0, 1, 0, -std::sin(theta), 0, std::cos(theta);
  rz << std::cos(psi), -std::sin(psi), 0, std::sin(psi), std::cos(psi), 0, 0, 0, 1;
  return rz * ry * rx;
}
}  // namespace

TEST(Pose, QuaternionFromRpyMatchesThesisMatrices) {
  Rng rng(3);
  for (int i = 0; i < 200; ++i) {
    const double r = rng.normal() , p = 0.7 * rng.normal(), y = 2 * rng.normal();
    EXPECT_LT((quat_from_rpy(r, p, y).toRotationMatrix() - rzyx(r, p, y)).norm(), 1e-12);
  }
}

TEST(Pose, RpyRoundTripsAwayFromGimbalLock) {
  Rng rng(5);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d rpy(std::numbers::pi * (2 * rng.uniform() - 1),
                              0.49 * std::numbers::pi * (2 * rng.uniform() - 1),
                              std::numbers::pi * (2 * rng.uniform() - 1));
    EXPECT_LT((rpy_from_quat(quat_from_rpy(rpy)) - rpy).norm(), 1e-9) << rpy.transpose();
  }
}

TEST(Pose, GimbalLockKeepsTheRotation) {
  const Eigen::Quaterniond q = quat_from_rpy(0.3, std::numbers::pi / 2, 0.5);
  const Eigen::Vector3d rpy = rpy_from_quat(q);
  EXPECT_DOUBLE_EQ(rpy.x(), 0.0);
  EXPECT_LT((quat_from_rpy(rpy).toRotationMatrix() - q.toRotationMatrix()).norm(), 1e-9);
}

TEST(Pose, OpticalToBodyAxes) {
  const Eigen::Matrix3d R = body_from_optical();
  // Camera forward (z_C) is body forward (x_B); camera right is starboard; camera down is down.
  EXPECT_EQ(R * Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
  EXPECT_EQ(R * Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  EXPECT_EQ(R * Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(R.determinant(), 1.0, 1e-15);
}

TEST(Pose, LevelFromBodyRemovesRollAndPitch) {
  const Pose T = level_from_body(0.2, -0.1);
  const Eigen::Vector3d rpy = rpy_from_matrix(T.linear());
  EXPECT_NEAR(rpy.x(), 0.2, 1e-12);
  EXPECT_NEAR(rpy.y(), -0.1, 1e-12);
  EXPECT_NEAR(rpy.z(), 0.0, 1e-12);
}

TEST(Pose, AxisAngleIsRodrigues) {
  const Eigen::Vector3d k = Eigen::Vector3d(1, 2, 3).normalized(), v(0.3, -1, 2);
  const double th = 0.8;
  const Eigen::Vector3d rod = v * std::cos(th) + k.cross(v) * std::sin(th) +
                              k * k.dot(v) * (1 - std::cos(th));  // eq. 2.5
  EXPECT_LT((quat_from_axis_angle(k * 4, th) * v - rod).norm(), 1e-12);
  EXPECT_NEAR(quat_from_axis_angle(k, th).w(), std::cos(th / 2), 1e-15);  // eq. 2.6
  EXPECT_THROW(quat_from_axis_angle(Eigen::Vector3d::Zero(), 1.0), Error);
}

}  // namespace uwgrasp
