#pragma once
// The camera model of thesis 3.1: a pinhole with Brown-Conrady distortion (OpenCV's plumb_bob:
// radial k1, k2, k3 and tangential p1, p2), and a stereo rig of two such cameras. Camera optical
// frame C: z forward, x right, y down; pixel centres at integer coordinates (OpenCV's).
#include <Eigen/Core>
#include <array>
#include <string>

namespace uwgrasp::camera {

struct Pinhole {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::array<double, 5> distortion{};  // k1, k2, p1, p2, k3

  // Pixel of a point in C (z > 0), distortion applied (eq. 3.1-3.3).
  Eigen::Vector2d project(const Eigen::Vector3d& p) const;
  // The ray (z = 1) through a pixel: distortion removed by fixed-point iteration (to 1e-12 on
  // the normalised coordinates, as OpenCV's undistortPoints with a tight criterion).
  Eigen::Vector3d unproject(const Eigen::Vector2d& pixel) const;
  // The normalised, undistorted coordinates distorted (x_d of eq. 3.2).
  Eigen::Vector2d distort(const Eigen::Vector2d& xy) const;
  bool distorted() const;
};

// A stereo rig: x_right = R x_left + T (OpenCV's stereoCalibrate convention), so the right
// camera's centre is at -R^T T in the left camera's frame.
struct StereoRig {
  Pinhole left, right;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d T = Eigen::Vector3d::Zero();
  double baseline() const { return T.norm(); }
};

// Throws Error naming `what` and the field for a size below 8 px, a non-positive or non-finite
// focal length, a principal point outside the image, non-finite distortion; for a rig, also a
// rotation that is not one and a zero baseline.
void check(const Pinhole& c, const std::string& what);
void check(const StereoRig& s, const std::string& what);

}  // namespace uwgrasp::camera
