// uwgrasp_node: ranked grasps for every cloud on `points` (docs/ros.md).
#include <ros/ros.h>

#include "node.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/memory.hpp"

int main(int argc, char** argv) {
  uwgrasp::keep_freed_memory();  // a stream of clouds: the first one's buffers serve the rest
  ros::init(argc, argv, "uwgrasp_node");
  ros::NodeHandle nh, pnh("~");
  try {
    uwgrasp_ros::Node node(nh, pnh);
    ros::AsyncSpinner spinner(2);  // callbacks and ~detect_once while a detection runs
    spinner.start();
    ros::waitForShutdown();
  } catch (const uwgrasp::Error& e) {
    ROS_FATAL("uwgrasp_node: %s", e.what());
    return 2;
  }
  return 0;
}
