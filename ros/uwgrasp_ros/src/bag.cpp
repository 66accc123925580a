#include "bag.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>
#include <tf2_msgs/TFMessage.h>

#include <cstring>
#include <filesystem>
#include <set>

#include "convert.hpp"
#include "tf_frames.hpp"
#include "uwgrasp/io/atomic_file.hpp"

namespace uwgrasp_ros {

using uwgrasp::Error;

namespace {
geometry_msgs::TransformStamped stamped(const Pose7& T, const ros::Time& t, const std::string& parent,
                                        const std::string& child) {
  geometry_msgs::TransformStamped s;
  s.header.stamp = t;
  s.header.frame_id = parent;
  s.child_frame_id = child;
  s.transform = transform_msg(T);
  return s;
}

void write_frame(rosbag::Bag& bag, const BagTopics& tp, const BagFrame& f) {
  const ros::Time t(f.time);
  std_msgs::Header h;
  h.stamp = t;
  h.frame_id = tp.camera_frame;
  sensor_msgs::PointCloud2 cloud = to_msg(f.cloud);
  cloud.header = h;
  sensor_msgs::Image rgb, depth;
  rgb.header = depth.header = h;
  rgb.width = depth.width = f.cloud.width;
  rgb.height = depth.height = f.cloud.height;
  rgb.encoding = "rgb8", rgb.step = rgb.width * 3;
  rgb.data.resize(std::size_t(rgb.step) * rgb.height);
  std::memcpy(rgb.data.data(), f.rgb.data(), std::min(rgb.data.size(), f.rgb.size()));
  depth.encoding = "16UC1", depth.step = depth.width * 2;
  depth.data.resize(std::size_t(depth.step) * depth.height);
  std::memcpy(depth.data.data(), f.depth.data(), std::min(depth.data.size(), f.depth.size() * 2));
  sensor_msgs::CameraInfo info;
  info.header = h;
  info.width = rgb.width, info.height = rgb.height;
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {f.fx, 0, f.cx, 0, f.fy, f.cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {f.fx, 0, f.cx, 0, 0, f.fy, f.cy, 0, 0, 0, 1, 0};
  sensor_msgs::Imu imu;
  imu.header.stamp = t;
  imu.header.frame_id = tp.base_frame;
  const auto& q = f.world_from_base.q;
  imu.orientation.x = q[0], imu.orientation.y = q[1], imu.orientation.z = q[2], imu.orientation.w = q[3];
  imu.angular_velocity_covariance[0] = imu.linear_acceleration_covariance[0] = -1;  // not measured
  tf2_msgs::TFMessage tf;
  tf.transforms.push_back(stamped(f.world_from_base, t, tp.world_frame, tp.base_frame));
  // Recorded a millisecond before the cloud, as they arrive on a vehicle: a reader in bag order
  // then has the cloud's transform and attitude when the cloud comes.
  const ros::Time before(f.time - 1e-3);
  bag.write("/tf", before, tf);
  bag.write(tp.imu, before, imu);
  bag.write(tp.info, t, info);
  bag.write(tp.rgb, t, rgb);
  bag.write(tp.depth, t, depth);
  bag.write(tp.points, t, cloud);
}
}  // namespace

void write_bag(const std::string& path, const BagTopics& tp, const Pose7& base_from_camera,
               const std::vector<BagFrame>& frames) {
  if (frames.empty()) throw Error(path + ": no frames to write");
  // Written whole or not at all (a temporary name, then a rename).
  uwgrasp::io::write_atomically(path, [&](const std::string& tmp) {
    try {
      rosbag::Bag bag(tmp, rosbag::bagmode::Write);
      bag.setCompression(rosbag::compression::LZ4);
      const ros::Time t0(frames.front().time);
      tf2_msgs::TFMessage st;
      st.transforms.push_back(stamped(base_from_camera, t0, tp.base_frame, tp.camera_frame));
      auto latched = boost::make_shared<ros::M_string>();
      (*latched)["latching"] = "1";  // rosbag play republishes /tf_static latched, as a driver does
      (*latched)["callerid"] = "/uwgrasp_simulate";
      (*latched)["type"] = ros::message_traits::datatype(st);  // with a header of its own, rosbag
      (*latched)["md5sum"] = ros::message_traits::md5sum(st);  // stores only what it is given
      (*latched)["message_definition"] = ros::message_traits::definition(st);
      bag.write("/tf_static", ros::Time(frames.front().time - 2e-3), st, latched);
      for (const auto& f : frames) write_frame(bag, tp, f);
      bag.close();
    } catch (const rosbag::BagException& e) {
      throw Error(path + ": cannot write the bag (" + e.what() + ")");
    }
  });
}

void for_each_cloud(const std::string& path, const std::string& topic, const std::string& imu_topic,
                    const std::string& base_frame, Stream& into,
                    const std::function<void(const BagCloud&)>& fn) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw Error(path + ": cannot read the bag (" + e.what() + ")");
  }
  rosbag::View all(bag);
  std::set<std::string> clouds;
  for (const auto* c : all.getConnections())
    if (c->datatype == "sensor_msgs/PointCloud2") clouds.insert(c->topic);
  if (!clouds.count(topic)) {
    std::string list;
    for (const auto& t : clouds) list += (list.empty() ? "" : ", ") + t;
    throw Error(path + ": no sensor_msgs/PointCloud2 on topic '" + topic + "' (the bag has: " +
                (list.empty() ? "none" : list) + ")");
  }
  tf2::BufferCore tf(ros::Duration(3600.0));
  std::optional<std::array<double, 2>> rp;
  rosbag::View view(bag, rosbag::TopicQuery({topic, imu_topic, "/tf", "/tf_static"}));
  for (const rosbag::MessageInstance& m : view) {
    if (m.getTopic() == "/tf" || m.getTopic() == "/tf_static") {
      if (const auto t = m.instantiate<tf2_msgs::TFMessage>())
        for (const auto& s : t->transforms) tf.setTransform(s, "bag", m.getTopic() == "/tf_static");
    } else if (!imu_topic.empty() && m.getTopic() == imu_topic) {
      if (const auto i = m.instantiate<sensor_msgs::Imu>()) {
        const auto& q = i->orientation;
        rp = roll_pitch_from({q.x, q.y, q.z, q.w});
      }
    } else if (const auto c = m.instantiate<sensor_msgs::PointCloud2>()) {
      BagCloud b;
      b.stamp = c->header.stamp.toSec();
      b.frame_id = c->header.frame_id;
      try {
        b.capture = capture_frames(tf, c->header, {base_frame, ""}, rp).capture;
        from_msg(*c, into);
      } catch (const std::exception& e) {
        b.error = e.what();
      }
      fn(b);
    }
  }
}

}  // namespace uwgrasp_ros
