#pragma once
// uwgrasp_node (docs/ros.md): clouds in, ranked grasps out. Always works on the newest cloud (a
// cloud replaced before it was processed counts as dropped); a bad message, frame or config
// update is one ROS_ERROR naming the problem and the node goes on with the next.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/String.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "engine.hpp"
#include "params.hpp"
#include "tf_frames.hpp"

namespace uwgrasp_ros {

class Node {
 public:
  // Throws uwgrasp::Error for a bad ~config or parameter (the node does not start). C++17.
  Node(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~Node();

 private:
  struct Pending {
    sensor_msgs::PointCloud2ConstPtr msg;
    std::chrono::steady_clock::time_point arrived;
  };
  void on_cloud(const sensor_msgs::PointCloud2ConstPtr& msg);
  void on_imu(const sensor_msgs::ImuConstPtr& msg);
  void on_odom(const nav_msgs::OdometryConstPtr& msg);
  // The capture roll and pitch from an IMU's or odometry's orientation (ROS body in ENU).
  void set_attitude(const geometry_msgs::Quaternion& q, const char* source);
  void on_set(const std_msgs::StringConstPtr& msg);
  bool on_detect_once(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool on_enable(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  void run();
  // Processes one cloud; false (with `why`) when the message, its frame or the config is bad.
  bool process(const Pending& p, std::string& why);
  CaptureFrames frames_of(const std_msgs::Header& h);
  void publish(const PlainDetection& d, const Pending& p, const CaptureFrames& frames);
  void diagnose(int level, const std::string& message, const PlainDetection* d, double latency_ms);

  ros::NodeHandle nh_, pnh_;
  NodeParams params_;
  Engine engine_;
  tf2_ros::Buffer tf_;
  tf2_ros::TransformListener tf_listener_;
  ros::Subscriber points_, imu_, odom_, set_;
  ros::Publisher grasps_, poses_, best_, vehicle_, markers_, diagnostics_;
  ros::ServiceServer detect_once_, enable_;
  std::mutex mutex_;       // guards the fields below and engine_
  std::mutex processing_;  // one detection at a time (worker or ~detect_once)
  Stream stream_;          // the frames' buffers, reused; guarded by processing_
  std::condition_variable wake_;
  std::optional<Pending> newest_;   // not yet processed
  sensor_msgs::PointCloud2ConstPtr last_;  // the newest cloud seen, for ~detect_once
  std::optional<std::array<double, 2>> roll_pitch_;  // from imu or odom
  bool enabled_ = true, stop_ = false;
  std::uint32_t processed_ = 0, dropped_ = 0, errors_ = 0;
  std::shared_ptr<void> thread_limit_;  // ~threads / config threads
  std::thread worker_;
};

}  // namespace uwgrasp_ros
