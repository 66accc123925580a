#pragma once
// The node's parameters: ~config (the same YAML as the CLI), the frames, and any config key as a
// private parameter (~grasp/sampler/samples: 500 is --set grasp.sampler.samples=500). C++17.
#include <ros/node_handle.h>

#include <string>
#include <vector>

namespace uwgrasp_ros {

struct NodeParams {
  std::string config_path;               // ~config: a uwgrasp YAML ("" = the compiled-in defaults)
  std::vector<std::string> sets;         // every other private parameter as "a.b.c=value"
  std::string base_frame = "base_link";  // ~base_frame ("" = the camera mount from the config)
  std::string fixed_frame;               // ~fixed_frame ("" = poses in the camera frame)
  double tf_timeout = 0.2;               // ~tf_timeout, s
  bool enabled = true;                   // ~enabled
};

// Reads the private parameters; throws uwgrasp::Error for a value of an unsupported type.
NodeParams read_params(const ros::NodeHandle& private_nh);

}  // namespace uwgrasp_ros
