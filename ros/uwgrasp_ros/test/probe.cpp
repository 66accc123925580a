// uwgrasp_probe: the other end of uwgrasp_node in the integration test (node_test.sh).
//   uwgrasp_probe listen OUT.jsonl N TIMEOUT_S   records what the node publishes until N GraspArrays,
//                                                 or until none came for 30 s after the first
//   uwgrasp_probe bad BAG OUT.jsonl TIMEOUT_S     sends malformed clouds, an unknown frame and a bad
//                                                 config key, then a good cloud; records the same;
//                                                 then disables the node, sends the good cloud
//                                                 (nothing may come), and calls ~detect_once
// Output: one JSON line per GraspArray ("grasps"), then one summary line ("summary").
#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Log.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/String.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <uwgrasp_msgs/GraspArray.h>
#include <visualization_msgs/MarkerArray.h>
#include <diagnostic_msgs/DiagnosticArray.h>

#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

namespace {
using nlohmann::json;

struct Recorder {
  std::vector<json> arrays;
  ros::WallTime last;  // when the newest GraspArray came
  json summary = {{"summary", true}, {"poses", 0}, {"markers", 0}, {"best", json::array()},
                  {"vehicle", 0}, {"diagnostics", 0}, {"errors", json::array()}};
  ros::Subscriber subs[7];

  explicit Recorder(ros::NodeHandle& nh) {
    subs[0] = nh.subscribe<uwgrasp_msgs::GraspArray>("/grasps", 50, [this](const auto& m) {
      json j = {{"stamp", m->header.stamp.toSec()}, {"frame_id", m->header.frame_id}, {"frame", m->frame},
                {"dropped", m->frames_dropped}, {"latency_ms", m->latency_ms}, {"grasps", json::array()}};
      for (const auto& g : m->grasps)
        j["grasps"].push_back({{"position", {g.pose.position.x, g.pose.position.y, g.pose.position.z}},
                               {"orientation_xyzw", {g.pose.orientation.x, g.pose.orientation.y,
                                                     g.pose.orientation.z, g.pose.orientation.w}},
                               {"score", g.score}, {"width", g.width}});
      arrays.push_back(j);
      last = ros::WallTime::now();
    });
    subs[1] = nh.subscribe<geometry_msgs::PoseArray>("/grasp_poses", 50, [this](const auto&) { summary["poses"] = int(summary["poses"]) + 1; });
    subs[2] = nh.subscribe<visualization_msgs::MarkerArray>("/markers", 50, [this](const auto& m) {
      if (m->markers.size() > 1) summary["markers"] = int(summary["markers"]) + 1;  // more than the DELETEALL
    });
    subs[3] = nh.subscribe<geometry_msgs::PoseStamped>("/best_grasp", 50, [this](const auto& m) {
      summary["best"].push_back({{"stamp", m->header.stamp.toSec()}, {"frame_id", m->header.frame_id},
                                 {"position", {m->pose.position.x, m->pose.position.y, m->pose.position.z}},
                                 {"orientation_xyzw", {m->pose.orientation.x, m->pose.orientation.y,
                                                       m->pose.orientation.z, m->pose.orientation.w}}});
    });
    subs[4] = nh.subscribe<geometry_msgs::PoseStamped>("/vehicle_target", 50, [this](const auto&) { summary["vehicle"] = int(summary["vehicle"]) + 1; });
    subs[5] = nh.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 50, [this](const auto&) { summary["diagnostics"] = int(summary["diagnostics"]) + 1; });
    subs[6] = nh.subscribe<rosgraph_msgs::Log>("/rosout", 100, [this](const auto& m) {
      if (m->level >= rosgraph_msgs::Log::ERROR && m->name.find("uwgrasp") != std::string::npos) summary["errors"].push_back(m->msg);
    });
  }

  void write(const std::string& path) const {
    std::ofstream out(path);
    for (const auto& a : arrays) out << a.dump() << "\n";
    out << summary.dump() << "\n";
  }
};

// Spins until `done` or the timeout; false on timeout or shutdown.
template <class F>
bool spin_until(F done, double timeout) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok() && !done()) {
    if (ros::WallTime::now() > end) return false;
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  return done();
}

// The bag's last cloud: its stamp is still in the node's tf cache after the bag played.
sensor_msgs::PointCloud2 last_cloud(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  sensor_msgs::PointCloud2::ConstPtr last;
  for (const auto& m : rosbag::View(bag))
    if (const auto c = m.instantiate<sensor_msgs::PointCloud2>()) last = c;
  if (!last) throw std::runtime_error(path + ": no PointCloud2");
  return *last;
}

// The malformed messages the node must survive, each with the word its error should contain.
std::vector<std::pair<sensor_msgs::PointCloud2, std::string>> bad_clouds(const sensor_msgs::PointCloud2& good) {
  std::vector<std::pair<sensor_msgs::PointCloud2, std::string>> out;
  auto m = good;
  m.fields.erase(m.fields.begin() + 1);  // no y
  out.emplace_back(m, "no field 'y'");
  m = good, m.point_step = 4;
  out.emplace_back(m, "point_step");
  m = good, m.data.resize(m.data.size() / 2);
  out.emplace_back(m, "bytes");
  m = good;
  for (std::size_t i = 0; i + 12 <= m.data.size(); i += m.point_step) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&m.data[i], &nan, 4), std::memcpy(&m.data[i + 4], &nan, 4), std::memcpy(&m.data[i + 8], &nan, 4);
  }
  out.emplace_back(m, "no finite point");
  m = good, m.width = 0, m.height = 0, m.data.clear(), m.row_step = 0;
  out.emplace_back(m, "empty");
  m = good, m.header.frame_id = "nowhere_optical";
  out.emplace_back(m, "nowhere_optical");
  return out;
}

int bad(ros::NodeHandle& nh, const std::string& bag, const std::string& out, double timeout) {
  Recorder rec(nh);
  auto pub = nh.advertise<sensor_msgs::PointCloud2>("/camera/depth/points", 10);
  auto set = nh.advertise<std_msgs::String>("/uwgrasp_node/set", 10, true);
  if (!spin_until([&] { return pub.getNumSubscribers() > 0 && set.getNumSubscribers() > 0 &&
                               rec.subs[6].getNumPublishers() > 0; }, timeout)) return 3;
  const sensor_msgs::PointCloud2 good = last_cloud(bag);
  std::size_t expected = 0;
  for (const auto& [msg, word] : bad_clouds(good)) {
    pub.publish(msg);
    ++expected;
    spin_until([&] { return rec.summary["errors"].size() >= expected; }, timeout);
  }
  std_msgs::String s;
  s.data = "grasp.no_such_key=1";
  set.publish(s);
  ++expected;
  spin_until([&] { return rec.summary["errors"].size() >= expected; }, timeout);
  pub.publish(good);  // the next good frame is processed
  spin_until([&] { return !rec.arrays.empty(); }, timeout);
  // Disabled, a cloud is kept but not processed; ~detect_once processes it.
  std_srvs::SetBool off;
  off.request.data = false;
  if (!ros::service::call("/uwgrasp_node/set_enabled", off)) return 4;
  pub.publish(good);
  spin_until([] { return false; }, 2.0);
  rec.summary["while_disabled"] = rec.arrays.size() - 1;
  std_srvs::Trigger once;
  if (!ros::service::call("/uwgrasp_node/detect_once", once)) return 5;
  rec.summary["detect_once"] = {{"success", bool(once.response.success)}, {"message", once.response.message}};
  spin_until([&] { return rec.arrays.size() >= 2; }, timeout);
  std_srvs::SetBool on;
  on.request.data = true;
  ros::service::call("/uwgrasp_node/set_enabled", on);
  ros::WallDuration(0.5).sleep();
  ros::spinOnce();
  rec.write(out);
  return 0;
}
}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "uwgrasp_probe", ros::init_options::AnonymousName);
  ros::NodeHandle nh;
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "listen" && argc == 5) {
    Recorder rec(nh);
    const std::size_t n = std::stoul(argv[3]);
    spin_until([&] { return rec.arrays.size() >= n ||
                            (!rec.arrays.empty() && ros::WallTime::now() - rec.last > ros::WallDuration(30.0)); },
               std::stod(argv[4]));
    ros::WallDuration(0.3).sleep();
    ros::spinOnce();
    rec.write(argv[2]);
    return 0;
  }
  if (mode == "bad" && argc == 5) return bad(nh, argv[2], argv[3], std::stod(argv[4]));
  std::fprintf(stderr, "usage: uwgrasp_probe listen OUT N TIMEOUT | bad BAG OUT TIMEOUT\n");
  return 2;
}
