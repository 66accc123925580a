// One cloud through uwgrasp_node: message -> cloud, frames through tf2, detection, publishing.
#include <geometry_msgs/PoseStamped.h>
#include <tf2/exceptions.h>

#include "convert.hpp"
#include "messages.hpp"
#include "node.hpp"

namespace uwgrasp_ros {

namespace {
double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

geometry_msgs::PoseStamped stamped(const Pose7& T, const std_msgs::Header& h, const std::string& frame) {
  geometry_msgs::PoseStamped p;
  p.header = h;
  p.header.frame_id = frame;
  p.pose = pose_msg(T);
  return p;
}
}  // namespace

// Waits up to ~tf_timeout for the cloud's transforms, then reads them (tf_frames.hpp).
CaptureFrames Node::frames_of(const std_msgs::Header& h) {
  std::optional<std::array<double, 2>> rp;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    rp = roll_pitch_;
  }
  const ros::Duration timeout(params_.tf_timeout);
  for (const auto& target : {params_.base_frame, params_.fixed_frame})
    if (!target.empty() && !h.frame_id.empty()) tf_.canTransform(target, h.frame_id, h.stamp, timeout);
  return capture_frames(tf_, h, {params_.base_frame, params_.fixed_frame}, rp);
}

bool Node::process(const Pending& p, std::string& why) {
  std::lock_guard<std::mutex> busy(processing_);
  const std_msgs::Header& h = p.msg->header;
  PlainDetection d;
  CaptureFrames frames;
  try {
    frames = frames_of(h);
    from_msg(*p.msg, stream_);  // read straight into the frame the engine detects on
    Engine engine = [&] {
      std::lock_guard<std::mutex> lock(mutex_);
      return engine_;
    }();
    d = engine.detect_frame(frames.capture, h.frame_id, UWGRASP_VERSION, stream_);
  } catch (const tf2::TransformException& e) {
    why = std::string("tf: ") + e.what();
  } catch (const std::exception& e) {
    why = e.what();
  }
  if (!why.empty()) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++errors_;
    diagnose(diagnostic_msgs::DiagnosticStatus::ERROR, why, nullptr, 0.0);
    return false;
  }
  if (!d.warning.empty()) ROS_WARN("uwgrasp_node: no grasp in the cloud at %.3f: %s", h.stamp.toSec(), d.warning.c_str());
  publish(d, p, frames);
  why = std::to_string(d.grasps.size()) + " grasps" +
        (d.grasps.empty() ? "" : ", best score " + std::to_string(d.grasps.front().score)) +
        (d.warning.empty() ? "" : " (" + d.warning + ")");
  return true;
}

void Node::publish(const PlainDetection& d, const Pending& p, const CaptureFrames& frames) {
  const std_msgs::Header& h = p.msg->header;
  uwgrasp_msgs::GraspArray arr = grasp_array(d, h);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    arr.frame = ++processed_;
    arr.frames_dropped = dropped_;
  }
  const std::string& fixed = params_.fixed_frame.empty() ? h.frame_id : params_.fixed_frame;
  if (!d.grasps.empty()) {
    const PlainGrasp& g = d.grasps.front();
    best_.publish(stamped(compose(frames.fixed_from_camera, g.pose), h, fixed));
    // The ROS base frame (x forward, y left, z up) the vehicle must bring to the grasp.
    vehicle_.publish(stamped(compose(compose(frames.fixed_from_camera, g.vehicle_pose), fossen_from_ros_body()), h, fixed));
  }
  markers_.publish(markers(d, h));
  poses_.publish(pose_array(arr));
  arr.latency_ms = ms_since(p.arrived);
  grasps_.publish(arr);
  std::lock_guard<std::mutex> lock(mutex_);
  diagnose(d.warning.empty() ? diagnostic_msgs::DiagnosticStatus::OK : diagnostic_msgs::DiagnosticStatus::WARN,
           d.warning.empty() ? std::to_string(d.grasps.size()) + " grasps" : d.warning, &d, arr.latency_ms);
}

// Called with mutex_ held.
void Node::diagnose(int level, const std::string& message, const PlainDetection* d, double latency_ms) {
  diagnostic_msgs::DiagnosticArray a;
  a.header.stamp = ros::Time::now();
  diagnostic_msgs::DiagnosticStatus s;
  s.level = static_cast<std::uint8_t>(level);
  s.name = ros::this_node::getName() + ": detection";
  s.hardware_id = "uwgrasp";
  s.message = message;
  const auto add = [&](const std::string& k, const std::string& v) {
    diagnostic_msgs::KeyValue kv;
    kv.key = k, kv.value = v;
    s.values.push_back(kv);
  };
  add("frames processed", std::to_string(processed_));
  add("frames dropped", std::to_string(dropped_));
  add("bad messages", std::to_string(errors_));
  if (d) {
    add("latency ms", std::to_string(latency_ms));
    for (const auto& st : d->stage_ms) add(st.first + " ms", std::to_string(st.second));
    add("total ms", std::to_string(d->total_ms));
    // preprocess.water.fallback: no object had the colour as the camera saw it.
    add("colours restored", d->colours_restored ? "true" : "false");
  }
  a.status.push_back(s);
  diagnostics_.publish(a);
}

}  // namespace uwgrasp_ros
