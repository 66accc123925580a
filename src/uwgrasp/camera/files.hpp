#pragma once
// Camera and stereo calibration files. Read: ROS camera_info YAML (camera_matrix,
// distortion_coefficients, image_width/height: what ROS's camera_calibration writes), OpenCV's
// FileStorage YAML or XML (camera_matrix / cameraMatrix / K / M1, distortion_coefficients /
// distCoeffs / D / D1, image_width/height or image_size; for a rig M1 D1 M2 D2 R T as OpenCV's
// stereo_calib writes, or K1 D1 K2 D2), and uwgrasp's own stereo file (image_width/height, left
// and right {K, D}, R, T: the simulator's stereo.yaml). Written: the ROS format for one camera,
// uwgrasp's for a rig.
#include <string>

#include "uwgrasp/camera/model.hpp"

namespace uwgrasp::camera {

// Throws Error naming the file and the field for an unreadable file, a missing or malformed
// matrix, distortion beyond plumb_bob's five coefficients, or a camera check() refuses.
Pinhole read_camera(const std::string& path);
StereoRig read_stereo(const std::string& path);

std::string camera_yaml(const Pinhole& c, const std::string& name = "camera");
std::string stereo_yaml(const StereoRig& s);

}  // namespace uwgrasp::camera
