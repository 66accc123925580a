#pragma once
// sensor_msgs/geometry_msgs <-> the bridge's plain types (engine.hpp). C++17 (ROS headers).
// A malformed PointCloud2 is a uwgrasp::Error naming the field, never a read out of bounds.
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <sensor_msgs/PointCloud2.h>

#include "engine.hpp"

namespace uwgrasp_ros {

// Reads x, y, z (FLOAT32 or FLOAT64) and rgb/rgba (packed in 4 bytes) when present. Throws for:
// no points, missing or non-float x/y/z, an unknown datatype, fields past point_step, big-endian
// data, row_step < width * point_step, data shorter than row_step * height. Organised messages
// stay organised.
PlainCloud from_msg(const sensor_msgs::PointCloud2& msg);
// The same into `out`, reusing its buffers (a node's stream of frames); on a throw `out` is
// unchanged.
void from_msg(const sensor_msgs::PointCloud2& msg, PlainCloud& out);
// The same straight into a stream's frame (Stream::frame), for Engine::detect_frame: the node's
// one copy of a message. On a throw the stream's frame is unchanged.
void from_msg(const sensor_msgs::PointCloud2& msg, Stream& out);

// x, y, z FLOAT32 and rgb (FLOAT32-packed, as PCL writes it) when the cloud has colours.
sensor_msgs::PointCloud2 to_msg(const PlainCloud& cloud);

Pose7 pose7(const geometry_msgs::Transform& t);
geometry_msgs::Transform transform_msg(const Pose7& p);
geometry_msgs::Pose pose_msg(const Pose7& p);

}  // namespace uwgrasp_ros
