#pragma once
// The frames of one cloud from tf, shared by uwgrasp_node and `uwgrasp detect --bag` so both give
// the same grasps: the camera mount from base_frame -> the cloud's frame, the capture roll and
// pitch from an IMU/odometry message or else from fixed_frame -> base_frame, and the camera's
// pose in fixed_frame for the published poses. C++17 (ROS headers).
#include <std_msgs/Header.h>
#include <tf2/buffer_core.h>

#include <optional>
#include <string>

#include "engine.hpp"

namespace uwgrasp_ros {

struct FrameNames {
  std::string base;   // the vehicle body (REP 103); "" = the camera mount from the config
  std::string fixed;  // a z-up world (ENU); "" = poses in the camera frame
};

struct CaptureFrames {
  Capture capture;
  Pose7 fixed_from_camera;  // identity without a fixed frame
};

// Throws tf2::TransformException when a transform is missing, uwgrasp::Error for a header
// without frame_id.
CaptureFrames capture_frames(const tf2::BufferCore& tf, const std_msgs::Header& h, const FrameNames& names,
                             const std::optional<std::array<double, 2>>& imu_roll_pitch);

}  // namespace uwgrasp_ros
