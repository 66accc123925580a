#pragma once
// A detection as ROS messages (docs/ros.md): the ranked grasps with every score (GraspArray),
// their poses (PoseArray), and RViz markers (gripper wireframes coloured by score, the object's
// points). Everything is in the frame of `header`, the cloud's. C++17 (ROS headers).
#include <geometry_msgs/PoseArray.h>
#include <std_msgs/Header.h>
#include <uwgrasp_msgs/GraspArray.h>
#include <visualization_msgs/MarkerArray.h>

#include "engine.hpp"

namespace uwgrasp_ros {

uwgrasp_msgs::GraspArray grasp_array(const PlainDetection& d, const std_msgs::Header& header);

geometry_msgs::PoseArray pose_array(const uwgrasp_msgs::GraspArray& grasps);

// First a DELETEALL (the previous frame's markers go), then one LINE_LIST per grasp in namespace
// "grippers" (id = rank; red = lowest score of the frame, green = highest; the best thicker and
// drawn last), and the object's points in namespace "object".
visualization_msgs::MarkerArray markers(const PlainDetection& d, const std_msgs::Header& header);

}  // namespace uwgrasp_ros
