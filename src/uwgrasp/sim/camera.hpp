#pragma once
// Pinhole camera (no distortion: the simulated lens is ideal; the camera module handles real
// lenses). Camera optical frame C: z forward, x right, y down.
#include <Eigen/Core>
#include <cstdint>

namespace uwgrasp::sim {

struct CameraConfig {
  std::uint32_t width = 640;
  std::uint32_t height = 480;
  double hfov = 1.047;      // horizontal field of view, rad (Gazebo's default camera)
  double max_range = 6.0;   // depth limit, m (thesis 7.4.1)
  double min_range = 0.05;  // closer surfaces give no depth, m
  double baseline = 0.12;   // stereo rig: right camera this far along the left camera's x, m
};

struct Intrinsics {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;

  // Pixel (u, v) of a point in C (z > 0); pixel centres are at integer coordinates.
  Eigen::Vector2d project(const Eigen::Vector3d& p) const {
    return {fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy};
  }
  // Ray direction in C through pixel (u, v), with z = 1 (so t along it is the depth).
  Eigen::Vector3d ray(double u, double v) const { return {(u - cx) / fx, (v - cy) / fy, 1.0}; }
};

// Square pixels, principal point at the image centre. Throws Error naming the field for a size
// below 8 pixels or above 8192, a field of view outside (0, pi), or ranges not 0 < min < max.
Intrinsics make_intrinsics(const CameraConfig& cfg);
void check_camera(const CameraConfig& cfg);

}  // namespace uwgrasp::sim
