#pragma once
// The Pinax model (thesis 3.2.1; Luczynski, Pfingsthorn and Birk 2017): a camera calibrated in
// air, behind a flat port, used under water. The port bends every ray (core/port), so the rays in
// water no longer meet in one point and the air pinhole is wrong. Pinax replaces it by a virtual
// pinhole camera (no distortion) on the optical axis where the in-water rays come closest to
// meeting, and a per-pixel map from the virtual image to the raw one, computed through the exact
// refraction for points at a reference distance. Matching, triangulation and the pipeline then
// work on the virtual images as on any pinhole camera's.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>

#include "uwgrasp/camera/model.hpp"
#include "uwgrasp/core/port.hpp"

namespace uwgrasp::camera {

struct Pinax {
  Pinhole air;  // the physical camera, calibrated in air (with its distortion)
  FlatPort port;
  Pinhole virtual_camera;  // same image size, no distortion
  double centre_z = 0.0;   // the virtual centre on the optical axis, in the camera's frame, m
  double reference = 2.0;  // m: the distance the map is exact at
  double spread = 0.0;     // RMS distance of the in-water rays from the virtual centre, m
  cv::Mat map_x, map_y;    // CV_32FC1: virtual pixel -> raw pixel (NaN-free; -1 outside)
};

// Throws Error (port.*) for a port check_port refuses, or one whose rays reflect totally inside
// the camera's field of view; `reference` must be beyond the port.
Pinax make_pinax(const Pinhole& air, const FlatPort& port, double reference = 2.0);

// The virtual pixel of a raw pixel (the exact refraction, then the virtual pinhole); nullopt
// when the ray does not leave the port.
std::optional<Eigen::Vector2d> virtual_pixel(const Pinax& p, const Eigen::Vector2d& raw);

// A point in the camera's frame from a point in the virtual camera's frame.
inline Eigen::Vector3d camera_from_virtual(const Pinax& p, const Eigen::Vector3d& x) {
  return x + Eigen::Vector3d(0.0, 0.0, p.centre_z);
}

}  // namespace uwgrasp::camera
