// uwgrasp demo [--out DIR]: the embedded default. Simulates the thesis scene (seafloor, barbell,
// ring on a pole, cross; Figure 8.1), detects grasps on each object with the session's settings
// (the defaults; --thesis: its Table 8.5 preset), writes grasps.json and grasps.png, and prints
// the best grasp per object. --sensor stereo: the cloud comes from the simulated stereo pair
// through the camera module (rectify, match, triangulate) instead of the depth camera.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/common.hpp"
#include "app/sensor.hpp"
#include "app/simulation.hpp"
#include "commands.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/atomic_file.hpp"
#include "uwgrasp/io/grasps_json.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace uwgrasp::app {

namespace {
struct DemoOptions {
  CommonOptions common;
  std::string out = "uwgrasp-demo";
  std::string water = "clear";
  bool noise = false;
  bool thesis = false;  // each object's Table 8.5 preset instead of the session's settings
  std::string sensor = "rgbd";
};

struct ObjectRun {
  std::string name;
  io::Config cfg;
  grasp::Detection d;
  double ms = 0;
};

ObjectRun detect_object(const Simulation& s, const sim::Frame& f, std::size_t i, const DemoOptions& o,
                        const io::Config& session, std::uint64_t seed) {
  ObjectRun run;
  run.name = s.scene.objects[i].name;
  run.cfg = o.thesis ? object_config(s, f, i, o.common.sets, seed) : pointed_at(session, s, f, i, seed);
  const auto t0 = std::chrono::steady_clock::now();
  run.d = grasp::detect(f.cloud, run.cfg.preprocess, run.cfg.segment, run.cfg.grasp, seed);
  run.ms = ms_since(t0);
  return run;
}

nlohmann::json demo_json(const std::vector<ObjectRun>& runs, const Simulation& s) {
  nlohmann::json j;
  j["uwgrasp_version"] = UWGRASP_VERSION;
  j["scene"] = s.scene.name;
  j["objects"] = nlohmann::json::array();
  for (const auto& r : runs) {
    nlohmann::json o = io::grasps_to_json(r.d, r.cfg, "cloud.pcd", UWGRASP_VERSION);
    o["name"] = r.name;
    j["objects"].push_back(std::move(o));
  }
  return j;
}

cv::Mat demo_picture(const std::vector<ObjectRun>& runs, const sim::Frame& f) {
  std::vector<viz::Wire> wires;
  std::vector<Eigen::Vector3f> focus;
  viz::Picture pic;
  pic.title = "uwgrasp demo: thesis scene, top grasps per object";
  for (const auto& r : runs) {
    const auto w = grasp_wires(r.d.result.grasps, r.d.result.frames, r.cfg.grasp.gripper);
    wires.insert(wires.end(), w.begin(), w.end());
    focus.insert(focus.end(), r.d.object.points.begin(), r.d.object.points.end());
    char line[160];
    std::snprintf(line, sizeof line, "%s: %s sampler, %zu feasible of %zu, best score %.3f", r.name.c_str(),
                  grasp::sampler_name(r.d.result.sampler), r.d.result.feasible(), r.d.result.candidates,
                  r.d.result.grasps.empty() ? 0.0 : r.d.result.grasps.front().scores.total);
    pic.legend.push_back(line);
  }
  return viz::draw(f.cloud, wires, pic, viz::View{}, focus);
}

// The demo's output directory: the frame, its truth, the images and the grasps.
void write_demo_files(const std::string& out, const Simulation& s, const sim::Frame& f,
                      const std::optional<sim::StereoFrame>& pair,
                      const std::vector<ObjectRun>& runs, std::uint64_t seed) {
  make_output_dir(out);
  const auto path = [&](const std::string& n) { return (std::filesystem::path(out) / n).string(); };
  io::save_cloud(path("cloud.pcd"), f.cloud);
  io::write_text(path("truth.yaml"),
                 io::truth_yaml(s.scene, truth_info(s, f.intrinsics, "rgbd", seed)));
  write_png(path("rgb.png"), viz::rgb_image(f.rgb, f.intrinsics.width, f.intrinsics.height));
  if (pair) {
    write_png(path("left.png"),
              viz::rgb_image(pair->left, f.intrinsics.width, f.intrinsics.height));
    write_png(path("right.png"),
              viz::rgb_image(pair->right, f.intrinsics.width, f.intrinsics.height));
    io::write_text(path("stereo.yaml"), io::stereo_yaml(*pair));
  }
  io::write_json(path("grasps.json"), demo_json(runs, s));
  write_png(path("grasps.png"), demo_picture(runs, f));
}

// One line per object: its sampler, candidates, best grasp and time.
void print_runs(const std::vector<ObjectRun>& runs) {
  std::printf(
      "  object   sampler  candidates  feasible  best score  width m  vehicle r/p/y deg   time "
      "ms\n");
  for (const auto& r : runs) {
    const auto& res = r.d.result;
    std::printf("  %-8s %-8s %10zu %9zu", r.name.c_str(), grasp::sampler_name(res.sampler),
                res.candidates, res.feasible());
    if (res.grasps.empty()) {
      std::printf("  %10s %8s %19s", "-", "-", "-");
    } else {
      const auto& g = res.grasps.front();
      const Eigen::Vector3d rpy = g.vehicle_rpy * (180.0 / 3.141592653589793);
      std::printf("  %10.3f %8.4f  %5.1f %5.1f %6.1f", g.scores.total, g.width, rpy.x(), rpy.y(),
                  rpy.z());
    }
    std::printf("  %8.0f\n", r.ms);
  }
}

int run_demo(const DemoOptions& o) {
  Session session = open_session(o.common);
  const std::uint64_t seed = session.config.seed;
  const auto t0 = std::chrono::steady_clock::now();
  // The thesis's conditions by default: clear water and a perfect sensor (7.4.1).
  io::Config sim_cfg = session.config;
  sim_cfg.sim.noise.enabled = o.noise;
  const Simulation s = make_simulation(sim_cfg, "thesis", o.water);
  progress("uwgrasp demo: rendering the thesis scene");
  const sim::World world(s.scene);
  const double build_ms = ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  sim::Frame f = sim::render_rgbd(world, s.world_from_camera, s.render, seed);
  double render_ms = ms_since(t1);
  std::optional<sim::StereoFrame> pair;
  StageTimer stereo_timer;
  if (o.sensor == "stereo") {
    // The depth camera's frame keeps the truth (labels); the cloud is the stereo rig's.
    const auto t2 = std::chrono::steady_clock::now();
    pair = sim::render_stereo(world, s.world_from_camera, s.render, seed);
    render_ms += ms_since(t2);
    sim::RenderConfig ideal = s.render;
    ideal.noise.enabled = false;
    const sim::Frame truth = sim::render_rgbd(world, s.world_from_camera, ideal, seed);
    camera::DenseFrame matched =
        simulated_stereo(*pair, session.config.stereo, std::nullopt, &stereo_timer);
    f.cloud = std::move(matched.cloud);
    use_matcher_error(session.config.grasp.shape, matched.depth_error);
    const DepthAccuracy a = depth_accuracy(f.cloud, truth, -1, 2.0);
    std::printf("stereo: rectify %.1f, match %.1f, cloud %.1f ms; depth up to 2 m: median error %.2f %%, %.1f %% of "
                "the pixels matched\n", stereo_timer.ms("rectify"), stereo_timer.ms("match"), stereo_timer.ms("cloud"),
                100 * a.median_error, 100 * a.completeness);
  }
  require_depth(f, s);
  std::vector<ObjectRun> runs;
  for (std::size_t i = 0; i < s.scene.objects.size(); ++i) {
    progress("uwgrasp demo: detecting grasps on the " + s.scene.objects[i].name);
    runs.push_back(detect_object(s, f, i, o, session.config, seed));
  }
  write_demo_files(o.out, s, f, pair, runs, seed);

  std::printf("scene %s (%s water, sensor noise %s) built in %.0f ms, %dx%d %s rendered in %.0f ms\n\n",
              s.scene.name.c_str(), s.render.water.preset.c_str(), o.noise ? "on" : "off", build_ms,
              f.intrinsics.width, f.intrinsics.height, pair ? "stereo pair (and RGB-D truth)" : "RGB-D frame",
              render_ms);
  print_runs(runs);
  std::printf("\nwrote %s: grasps.json grasps.png cloud.pcd rgb.png truth.yaml%s (%.1f s in all)\n",
              o.out.c_str(), pair ? " left.png right.png stereo.yaml" : "", ms_since(t0) / 1000.0);
  return 0;
}
}  // namespace

void add_demo_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners) {
  auto* cmd = app.add_subcommand("demo", "Simulate the thesis scene and find grasps on each object");
  auto o = std::make_shared<DemoOptions>();
  cmd->add_option("--out", o->out, "Output directory")->capture_default_str();
  cmd->add_option("--water", o->water, "Water preset")->check(CLI::IsMember({"clear", "coastal", "turbid"}))
      ->capture_default_str();
  cmd->add_flag("--noise", o->noise, "Depth noise, dropouts and marine snow (default: the thesis's perfect sensor)");
  cmd->add_option("--sensor", o->sensor, "rgbd: the depth camera; stereo: the rig's pair matched into the cloud")
      ->check(CLI::IsMember({"rgbd", "stereo"}))->capture_default_str();
  cmd->add_flag("--thesis", o->thesis, "Detect with each object's Table 8.5 preset (config/thesis_*.yaml)");
  add_common(*cmd, o->common);
  runners.emplace_back(cmd, [o] { return run_demo(*o); });
}

}  // namespace uwgrasp::app
