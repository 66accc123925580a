#pragma once
// Rosbags of camera frames: written by `uwgrasp simulate --bag` as a vehicle's drivers would
// record them, read back by `uwgrasp detect --bag` one cloud at a time with tf and the IMU.
// Plain types only (engine.hpp), so the C++20 CLI can include it; bag.cpp is C++17.
#include <functional>
#include <string>
#include <vector>

#include "engine.hpp"

namespace uwgrasp_ros {

struct BagTopics {
  std::string points = "/camera/depth/points";
  std::string rgb = "/camera/color/image_raw";
  std::string depth = "/camera/depth/image_raw";
  std::string info = "/camera/color/camera_info";
  std::string imu = "/imu/data";
  std::string world_frame = "world", base_frame = "base_link", camera_frame = "camera_optical";
};

struct BagFrame {
  double time = 0.0;  // s since the epoch
  PlainCloud cloud;   // organised, camera optical frame
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::vector<std::uint8_t> rgb;      // width x height x 3
  std::vector<std::uint16_t> depth;   // mm, 0 = none
  Pose7 world_from_base;              // ROS base frame (x forward, y left, z up) in a z-up world
};

// Writes every frame: the cloud, the colour and depth images with camera_info, the IMU
// orientation of the base frame, /tf (world -> base at every frame) and /tf_static (base ->
// camera, latched). Written to PATH.tmp then renamed: no partial bag. Throws uwgrasp::Error.
void write_bag(const std::string& path, const BagTopics& topics, const Pose7& base_from_camera,
               const std::vector<BagFrame>& frames);

// One cloud of a bag; its points are in the reader's Stream (Stream::frame).
struct BagCloud {
  double stamp = 0.0;
  std::string frame_id;
  Capture capture;     // from the bag's tf (base -> cloud frame) and IMU
  std::string error;   // a malformed message or a missing transform ("" = fine)
};

// Calls `fn` for each PointCloud2 on `topic`, in time order, with the cloud read into `into`'s
// frame (for Engine::detect_frame) and the capture from the bag's /tf, /tf_static (base_frame ->
// the cloud's frame) and the newest message on `imu_topic` before it ("" = none). Throws
// uwgrasp::Error naming the bag for an unreadable bag or a topic that has no PointCloud2 (listing
// the topics that have).
void for_each_cloud(const std::string& path, const std::string& topic, const std::string& imu_topic,
                    const std::string& base_frame, Stream& into,
                    const std::function<void(const BagCloud&)>& fn);

}  // namespace uwgrasp_ros
