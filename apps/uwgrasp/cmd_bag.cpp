// simulate --bag and detect --bag (bag_commands.hpp).
#include <algorithm>
#include <cstdio>

#include "bag_commands.hpp"
#include "app/common.hpp"
#include "uwgrasp/core/error.hpp"

#ifdef UWGRASP_WITH_ROS
#include "bag.hpp"
#include "engine_config.hpp"
#include "uwgrasp/io/atomic_file.hpp"
#include <nlohmann/json.hpp>
#endif

namespace uwgrasp::app {

#ifndef UWGRASP_WITH_ROS
void simulate_bag(const Simulation&, const io::Config&, const BagOptions& o) {
  throw Error("--bag " + o.bag + ": this uwgrasp was built without ROS 1 (configure with UWGRASP_BUILD_ROS=ON)");
}
int detect_bag(const BagOptions& o, const io::Config&, const std::string&) {
  throw Error("--bag " + o.bag + ": this uwgrasp was built without ROS 1 (configure with UWGRASP_BUILD_ROS=ON)");
}
#else
namespace {
double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * double(v.size() - 1) + 0.5)];
}
}  // namespace

void simulate_bag(const Simulation& s, const io::Config& cfg, const BagOptions& o) {
  if (o.frames < 1 || !(o.rate > 0.0)) throw Error("--frames must be >= 1 and --rate > 0");
  const sim::World world(s.scene);
  const uwgrasp_ros::Pose7 flu = uwgrasp_ros::fossen_from_ros_body();
  // The vehicle holds station: T_WB from the camera pose and its mount; ROS base frames are FLU.
  const Pose T_WB = s.world_from_camera * body_from_camera(s.mount).inverse();
  std::vector<uwgrasp_ros::BagFrame> frames;
  for (int i = 0; i < o.frames; ++i) {
    progress("uwgrasp simulate: frame " + std::to_string(i + 1) + " of " + std::to_string(o.frames));
    const sim::Frame f = sim::render_rgbd(world, s.world_from_camera, s.render, cfg.seed + std::uint64_t(i));
    uwgrasp_ros::BagFrame b;
    b.time = 1.7e9 + double(i) / o.rate;  // fixed: same seed, same bag
    b.cloud = uwgrasp_ros::plain_cloud(f.cloud);
    b.fx = f.intrinsics.fx, b.fy = f.intrinsics.fy, b.cx = f.intrinsics.cx, b.cy = f.intrinsics.cy;
    for (const auto& k : f.rgb) b.rgb.insert(b.rgb.end(), {k.r, k.g, k.b});
    b.depth = f.depth;
    b.world_from_base = uwgrasp_ros::compose(uwgrasp_ros::pose7(T_WB), flu);
    frames.push_back(std::move(b));
  }
  const auto base_from_camera = uwgrasp_ros::compose(uwgrasp_ros::inverse(flu), uwgrasp_ros::pose7(body_from_camera(s.mount)));
  uwgrasp_ros::write_bag(o.bag, uwgrasp_ros::BagTopics{}, base_from_camera, frames);
  std::printf("wrote %s: %d frames at %.1f Hz on %s (+ images, camera_info, /imu/data, /tf, /tf_static)\n",
              o.bag.c_str(), o.frames, o.rate, uwgrasp_ros::BagTopics{}.points.c_str());
}

int detect_bag(const BagOptions& o, const io::Config& cfg, const std::string& jsonl) {
  const uwgrasp_ros::Engine engine = uwgrasp_ros::make_engine(cfg);
  uwgrasp_ros::Stream stream;  // the frames' buffers, reused
  std::string lines;
  std::vector<double> ms;
  std::size_t n = 0, with_grasps = 0, bad = 0;
  uwgrasp_ros::for_each_cloud(
      o.bag, o.topic, o.imu_topic, o.base_frame, stream, [&](const uwgrasp_ros::BagCloud& b) {
        ++n;
        progress("uwgrasp detect: frame " + std::to_string(n));
        if (!b.error.empty()) {
          ++bad;
          std::printf("frame %zu at %.3f: skipped: %s\n", n, b.stamp, b.error.c_str());
          return;
        }
        uwgrasp_ros::PlainDetection d;
        try {
          d = engine.detect_frame(b.capture, b.frame_id, UWGRASP_VERSION, stream);
        } catch (const Error& e) {
          ++bad;
          std::printf("frame %zu at %.3f: skipped: %s\n", n, b.stamp, e.what());
          return;
        }
        with_grasps += !d.grasps.empty();
        ms.push_back(d.total_ms);
        nlohmann::json j = d.json.empty() ? nlohmann::json{{"grasps", nlohmann::json::array()},
                                                           {"warning", d.warning}}
                                          : nlohmann::json::parse(d.json);
        j["stamp"] = b.stamp;
        j["frame_id"] = b.frame_id;
        lines += j.dump() + "\n";
        std::printf("frame %zu at %.3f: %zu grasps%s, %.1f ms\n", n, b.stamp, d.grasps.size(),
                    d.grasps.empty() ? (" (" + d.warning + ")").c_str() : "", d.total_ms);
      });
  std::printf("%zu frames on %s: %zu with grasps, %zu skipped; detection median %.1f ms, 95th percentile %.1f ms\n",
              n, o.topic.c_str(), with_grasps, bad, percentile(ms, 0.5), percentile(ms, 0.95));
  if (!jsonl.empty()) {
    io::write_text(jsonl, lines);
    std::printf("wrote %s (one grasps.json per frame)\n", jsonl.c_str());
  }
  return 0;
}
#endif

}  // namespace uwgrasp::app
