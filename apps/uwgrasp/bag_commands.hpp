#pragma once
// The CLI's rosbag options (simulate --bag, detect --bag): available when uwgrasp is built with
// ROS 1 (UWGRASP_BUILD_ROS); otherwise they are an Error saying so.
#include <string>

#include "app/simulation.hpp"

namespace uwgrasp::app {

struct BagOptions {
  std::string bag;
  std::string topic = "/camera/depth/points";
  std::string imu_topic = "/imu/data";   // "" = none
  std::string base_frame = "base_link";  // "" = the camera mount from the config
  int frames = 20;
  double rate = 2.0;  // Hz
};

// Renders opts.frames frames of the simulation (noise seeds seed, seed + 1, ...) from a vehicle
// holding station, and writes them as a rosbag: cloud, images, camera_info, tf, imu.
void simulate_bag(const Simulation& s, const io::Config& cfg, const BagOptions& opts);

// Detects on every PointCloud2 of opts.topic; writes one grasps.json per line to `jsonl` (if not
// empty) and prints a line per frame and a summary. Returns the exit code.
int detect_bag(const BagOptions& opts, const io::Config& cfg, const std::string& jsonl);

}  // namespace uwgrasp::app
