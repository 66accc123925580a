#pragma once
// Triangulation (thesis 3.6.1): the direct linear transform solved by an SVD, and a stereo rig's
// triangulator from raw pixel pairs (lens distortion removed; behind a flat port, each pixel
// taken to its Pinax virtual camera first).
#include <Eigen/Core>
#include <optional>

#include "uwgrasp/camera/model.hpp"
#include "uwgrasp/camera/pinax.hpp"

namespace uwgrasp::camera {

using Projection = Eigen::Matrix<double, 3, 4>;

// The point X with x1 ~ P1 X and x2 ~ P2 X, minimising the algebraic error of the four DLT
// equations (x (P row 3) - (P row 1)) X = 0, ... (eq. 3.27): the right singular vector of the
// smallest singular value, de-homogenised. Exact for noiseless projections.
Eigen::Vector3d triangulate_dlt(const Projection& P1, const Projection& P2,
                                const Eigen::Vector2d& x1, const Eigen::Vector2d& x2);

// The rig of two Pinax virtual cameras: each virtual frame is its camera's moved by centre_z
// along its axis, so x_r' = R x_l' + T' with T' = T + c_l R e_z - c_r e_z.
StereoRig virtual_rig(const StereoRig& air, const Pinax& left, const Pinax& right);

class Triangulator {
 public:
  // Throws Error for a rig check() refuses or a port make_pinax refuses.
  explicit Triangulator(const StereoRig& rig, const std::optional<FlatPort>& port = std::nullopt,
                        double port_reference = 2.0);
  // The point in the (physical) left camera's optical frame seen at raw pixels a (left) and b
  // (right); nullopt when a pixel's ray does not leave the port.
  std::optional<Eigen::Vector3d> point(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  // The undistorted normalised coordinates (z = 1) of a raw pixel in the rig that triangulates.
  std::optional<Eigen::Vector3d> left_ray(const Eigen::Vector2d& a) const;
  std::optional<Eigen::Vector3d> right_ray(const Eigen::Vector2d& b) const;
  const StereoRig& rig() const { return used_; }  // the virtual rig behind a port

 private:
  StereoRig used_;
  std::optional<Pinax> left_, right_;
};

}  // namespace uwgrasp::camera
