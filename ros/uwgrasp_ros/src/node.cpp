#include "node.hpp"

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <uwgrasp_msgs/GraspArray.h>
#include <visualization_msgs/MarkerArray.h>

#include <tbb/global_control.h>

#include <sstream>


namespace uwgrasp_ros {

using uwgrasp::Error;


Node::Node(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(nh), pnh_(pnh), params_(read_params(pnh)), engine_(params_.config_path, params_.sets), tf_listener_(tf_) {
  enabled_ = params_.enabled;
  if (engine_.threads() > 0)
    thread_limit_ = std::make_shared<tbb::global_control>(tbb::global_control::max_allowed_parallelism, engine_.threads());
  grasps_ = nh_.advertise<uwgrasp_msgs::GraspArray>("grasps", 2);
  poses_ = nh_.advertise<geometry_msgs::PoseArray>("grasp_poses", 2);
  best_ = nh_.advertise<geometry_msgs::PoseStamped>("best_grasp", 2);
  vehicle_ = nh_.advertise<geometry_msgs::PoseStamped>("vehicle_target", 2);
  markers_ = nh_.advertise<visualization_msgs::MarkerArray>("markers", 2);
  diagnostics_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10);
  points_ = nh_.subscribe("points", 1, &Node::on_cloud, this);
  imu_ = nh_.subscribe("imu", 10, &Node::on_imu, this);
  odom_ = nh_.subscribe("odom", 10, &Node::on_odom, this);
  set_ = pnh_.subscribe("set", 10, &Node::on_set, this);
  detect_once_ = pnh_.advertiseService("detect_once", &Node::on_detect_once, this);
  enable_ = pnh_.advertiseService("set_enabled", &Node::on_enable, this);
  worker_ = std::thread([this] { run(); });
  ROS_INFO("uwgrasp_node: listening on %s (base frame '%s', fixed frame '%s', %s)", points_.getTopic().c_str(),
           params_.base_frame.c_str(), params_.fixed_frame.c_str(), enabled_ ? "enabled" : "disabled");
}

Node::~Node() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void Node::on_cloud(const sensor_msgs::PointCloud2ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (newest_) ++dropped_;
  last_ = msg;
  if (!enabled_) return;
  newest_ = Pending{msg, std::chrono::steady_clock::now()};
  wake_.notify_one();
}

void Node::on_imu(const sensor_msgs::ImuConstPtr& msg) { set_attitude(msg->orientation, "imu"); }

void Node::on_odom(const nav_msgs::OdometryConstPtr& msg) { set_attitude(msg->pose.pose.orientation, "odom"); }

void Node::set_attitude(const geometry_msgs::Quaternion& q, const char* source) {
  try {
    const auto rp = roll_pitch_from({q.x, q.y, q.z, q.w});
    std::lock_guard<std::mutex> lock(mutex_);
    roll_pitch_ = rp;
  } catch (const Error& e) {
    ROS_ERROR("uwgrasp_node: %s message ignored: %s", source, e.what());
  }
}

void Node::on_set(const std_msgs::StringConstPtr& msg) {
  std::vector<std::string> sets;
  std::istringstream in(msg->data);
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t") != std::string::npos) sets.push_back(line);
  std::lock_guard<std::mutex> lock(mutex_);
  try {
    engine_.update(sets);
    ROS_INFO("uwgrasp_node: config updated (%zu keys)", sets.size());
  } catch (const Error& e) {
    ++errors_;
    ROS_ERROR("uwgrasp_node: config update refused, the config is unchanged: %s", e.what());
  }
}

bool Node::on_enable(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
  std::lock_guard<std::mutex> lock(mutex_);
  enabled_ = req.data;
  if (!enabled_) newest_.reset();
  res.success = true;
  res.message = enabled_ ? "enabled" : "disabled";
  return true;
}

bool Node::on_detect_once(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  Pending p;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    p = Pending{last_, std::chrono::steady_clock::now()};
  }
  if (!p.msg) {
    res.success = false;
    res.message = "no cloud received yet on " + points_.getTopic();
    return true;
  }
  std::string why;
  res.success = process(p, why);
  res.message = res.success ? why : "error: " + why;
  return true;
}

void Node::run() {
  while (true) {
    Pending p;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || newest_; });
      if (stop_) return;
      p = *newest_;
      newest_.reset();
    }
    std::string why;
    if (!process(p, why)) ROS_ERROR("uwgrasp_node: cloud at %.3f in '%s' skipped: %s", p.msg->header.stamp.toSec(),
                                     p.msg->header.frame_id.c_str(), why.c_str());
  }
}

}  // namespace uwgrasp_ros
