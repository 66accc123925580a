// uwgrasp detect CLOUD | --stereo LEFT RIGHT --calib F | --rgbd DEPTH RGB --camera F: the full
// pipeline (thesis ch. 3-6) on a cloud in the camera optical frame, or on the one a stereo or
// RGB-D pair gives; prints the best grasp and per-stage times, optionally writes grasps.json.
#include <cstdio>

#include "app/common.hpp"
#include "app/frame.hpp"
#include "app/sensor.hpp"
#include "app/simulation.hpp"
#include "bag_commands.hpp"
#include "commands.hpp"
#include "detect_report.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/grasps_json.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace uwgrasp::app {

namespace {
struct DetectOptions {
  CommonOptions common;
  SensorOptions sensor;
  FrameOptions frame;
  BagOptions bag;
  std::string cloud, object, sampler, json, png;
  std::int64_t samples = -1, top = -1;
};

// --object color:NAME | label:N | point:X,Y,Z | nearest | largest, as config overrides.
void object_overrides(const std::string& o, std::vector<std::string>& sets) {
  if (o.empty()) return;
  const auto colon = o.find(':');
  const std::string by = o.substr(0, colon), arg = colon == std::string::npos ? "" : o.substr(colon + 1);
  const bool plain = (by == "nearest" || by == "largest") && colon == std::string::npos;
  const bool with_arg = (by == "color" || by == "label" || by == "point") && !arg.empty();
  if (!plain && !with_arg)
    throw Error("--object '" + o + "': expected color:NAME, label:N, point:X,Y,Z, nearest or largest");
  sets.push_back("segment.object.by=" + by);
  if (with_arg) sets.push_back("segment.object." + by + "=" + (by == "point" ? "[" + arg + "]" : arg));
}

void add_detect_options(CLI::App& cmd, DetectOptions& o) {
  cmd.add_option("CLOUD", o.cloud,
                 ".pcd or .ply cloud (or --stereo, --rgbd), in the camera optical frame unless "
                 "its VIEWPOINT or --camera-pose gives the camera pose");
  add_sensor_options(cmd, o.sensor);
  add_frame_options(cmd, o.frame);
  cmd.add_option("--bag", o.bag.bag,
                 "Every PointCloud2 of --topic in this rosbag (ROS builds); --json "
                 "then writes one grasps.json per line (JSON Lines)");
  cmd.add_option("--topic", o.bag.topic, "The bag's cloud topic (camera optical frame)")
      ->capture_default_str();
  cmd.add_option("--imu-topic", o.bag.imu_topic,
                 "The bag's IMU topic for the capture roll/pitch (\"\" = none)")
      ->capture_default_str();
  cmd.add_option("--base-frame", o.bag.base_frame,
                 "The vehicle's tf frame: the camera mount comes from tf "
                 "(\"\" = from the config)")
      ->capture_default_str();
  cmd.add_option(
      "--object", o.object,
      "Object of interest: color:NAME, label:N, point:X,Y,Z (the cloud's frame), nearest, largest");
  cmd.add_option("--sampler", o.sampler, "Candidate sampler")
      ->check(CLI::IsMember({"antipodal", "uniform", "normal", "surface", "auto"}));
  cmd.add_option("--samples", o.samples, "Number of candidates")->check(CLI::Range(1, 100000000));
  cmd.add_option("--top", o.top, "Grasps kept after ranking")->check(CLI::Range(1, 1000000));
  cmd.add_option("--json", o.json, "Write grasps.json (INTERFACE.md) here");
  cmd.add_option("--png", o.png, "Draw the cloud and the ranked grasps (coloured by score) here");
  add_common(cmd, o.common);
}

// The options that are config values, as --set overrides on top of --config and --set.
CommonOptions with_overrides(const DetectOptions& o) {
  CommonOptions common = o.common;
  object_overrides(o.object, common.sets);
  if (!o.sampler.empty()) common.sets.push_back("grasp.sampler.kind=" + o.sampler);
  if (o.samples > 0) common.sets.push_back("grasp.sampler.samples=" + std::to_string(o.samples));
  if (o.top > 0) common.sets.push_back("grasp.score.top=" + std::to_string(o.top));
  return common;
}

// The cloud to detect on, in the camera frame: a file's, or the one a stereo or RGB-D pair
// gives. The sensor's cloud lives only until it is in the camera frame (not a second frame for
// the whole detection). A stereo pair's depth is smoother than it is right: its matcher's error
// floors the surface noise (grasp.shape.depth_error; a cloud file's source is not known: set it
// for one).
CameraCloud detect_input(const DetectOptions& o, io::Config& cfg, std::string& name) {
  StageTimer sensor_timer;
  const bool images = o.sensor.any();
  progress("uwgrasp detect: loading " + (images ? std::string("images") : o.cloud));
  if (images && (!o.frame.camera_pose.empty() || o.frame.frame == "world"))
    throw Error(
        "--camera-pose and --frame world apply to a CLOUD file: images give a cloud in "
        "the camera optical frame");
  double sensed_error = 0.0;
  CameraCloud in = [&] {
    const SensorCloud sensed = images || o.cloud.empty()
                                   ? sensor_input(o.sensor, o.cloud, cfg.stereo, sensor_timer, name)
                                   : SensorCloud{io::load_cloud(o.cloud), 0.0};
    sensed_error = sensed.depth_error;
    return to_camera_frame(sensed.cloud, o.frame, name);
  }();
  use_matcher_error(cfg.grasp.shape, sensed_error);
  if (images) {
    std::printf("images to cloud (ms):");
    for (const auto& st : sensor_timer.stages()) std::printf(" %s %.1f |", st.name.c_str(), st.ms);
    std::printf(" total %.1f\n", sensor_timer.total_ms());
  }
  return in;
}

int run_detect(const DetectOptions& o) {
  Session session = open_session(with_overrides(o));
  io::Config& cfg = session.config;
  if (!o.bag.bag.empty()) {
    if (o.sensor.any() || !o.cloud.empty() || !o.png.empty())
      throw Error("--bag takes the clouds from the bag: without CLOUD, --stereo, --rgbd or --png");
    return detect_bag(o.bag, cfg, o.json);
  }
  std::string name = o.cloud;
  const CameraCloud in = detect_input(o, cfg, name);
  const Cloud& input = in.cloud;
  // --object point:X,Y,Z is in the cloud's frame, like every other coordinate the user sees.
  if (o.object.rfind("point:", 0) == 0)
    cfg.segment.object.point = in.frame.from_camera.inverse() * cfg.segment.object.point;
  progress("uwgrasp detect: " + std::to_string(input.size()) + " points, detecting");
  const grasp::Detection d = about_input(
      name, [&] { return grasp::detect(input, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed); });
  std::printf("path: %s\nframe: %s\n", cloud::path_summary(input, cfg.preprocess).c_str(),
              in.summary.c_str());
  print_level(d, cfg.grasp.frames);
  print_detection(name, d, cfg, in.frame);
  if (!o.json.empty()) {
    io::write_json(o.json, io::grasps_to_json(d, cfg, name, UWGRASP_VERSION, in.frame));
    std::printf("wrote %s\n", o.json.c_str());
  }
  if (!o.png.empty()) {
    write_png(o.png, detection_picture(input, d, cfg, name));
    std::printf("wrote %s\n", o.png.c_str());
  }
  return 0;
}
}  // namespace

void add_detect_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners) {
  auto* cmd = app.add_subcommand("detect", "Find ranked grasps on the object of interest in a cloud");
  auto o = std::make_shared<DetectOptions>();
  add_detect_options(*cmd, *o);
  runners.emplace_back(cmd, [o] { return run_detect(*o); });
}

}  // namespace uwgrasp::app
