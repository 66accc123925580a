// uwgrasp simulate --scene NAME|FILE.yaml [--water W] [--sensor rgbd|stereo] --out DIR: renders
// a scene with the virtual RGB-D camera (and stereo rig) and writes the images, the organised
// cloud and the ground truth (INTERFACE.md).
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/common.hpp"
#include "bag_commands.hpp"
#include "commands.hpp"
#include "app/simulation.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/atomic_file.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace uwgrasp::app {

namespace {
struct SimulateOptions {
  CommonOptions common;
  std::string scene, water, sensor = "rgbd", out, port, frame = "camera";
  bool object_only = false;
  BagOptions bag;
};

std::string port_yaml(const FlatPort& p) {
  char text[256];
  std::snprintf(text, sizeof text,
                "# the camera housing's flat port (uwgrasp simulate --port / stereo --port)\n"
                "distance: %.9g\nthickness: %.9g\nn_air: %.9g\nn_glass: %.9g\nn_water: %.9g\n",
                p.distance, p.thickness, p.n_air, p.n_glass, p.n_water);
  return text;
}

// The points that show the object of interest (truth labels), unorganised: an object-only cloud
// as segmented-out clouds and fused scans come.
Cloud object_points(const sim::Frame& f, const sim::Scene& scene) {
  std::vector<std::uint32_t> keep;
  for (std::size_t k = 0; k < scene.objects.size(); ++k) {
    if (!scene.objects[k].interest) continue;
    for (std::size_t i = 0; i < f.labels.size(); ++i)
      if (f.labels[i] == sim::kLabelFirstObject + k && is_finite(f.cloud.points[i]))
        keep.push_back(static_cast<std::uint32_t>(i));
  }
  if (keep.empty()) throw Error("--object-only: the camera sees no point of the scene's object of interest");
  return select(f.cloud, keep);
}

// The simulation's output directory: the cloud, the images, the truth and the config to detect
// on it with.
void write_simulation(const SimulateOptions& o, const Simulation& s, const sim::Frame& f,
                      const std::optional<sim::StereoFrame>& stereo, const io::Config& config) {
  make_output_dir(o.out);
  const auto path = [&](const char* name) {
    return (std::filesystem::path(o.out) / name).string();
  };
  const int w = f.intrinsics.width, h = f.intrinsics.height;
  // In the world frame the camera pose goes into the PCD VIEWPOINT (how many tools write clouds).
  const Cloud cloud = o.object_only ? object_points(f, s.scene) : f.cloud;
  io::save_cloud(path("cloud.pcd"),
                 o.frame == "world" ? transformed(cloud, s.world_from_camera) : cloud);
  write_png(path("rgb.png"), viz::rgb_image(f.rgb, w, h));
  write_png(path("depth.png"), viz::depth_image(f.depth, w, h));
  write_png(path("labels.png"), viz::depth_image(f.labels, w, h));
  if (stereo) {
    write_png(path("left.png"), viz::rgb_image(stereo->left, w, h));
    write_png(path("right.png"), viz::rgb_image(stereo->right, w, h));
    io::write_text(path("stereo.yaml"), io::stereo_yaml(*stereo));
  }
  if (s.render.port) io::write_text(path("port.yaml"), port_yaml(*s.render.port));
  io::write_text(path("truth.yaml"),
                 io::truth_yaml(s.scene, truth_info(s, f.intrinsics, o.sensor, config.seed)));
  io::Config detect_cfg = config;
  use_simulation_frames(detect_cfg, s);
  io::write_text(path("config.yaml"), io::to_yaml(detect_cfg));
}

int run_simulate(const SimulateOptions& o) {
  Session session = open_session(o.common);
  Simulation s = make_simulation(session.config, o.scene, o.water);
  if (!o.port.empty()) {
    s.scene.port = io::load_port(o.port);
    check_port(*s.scene.port);
    s.render.port = s.scene.port;
  }
  if (!o.bag.bag.empty()) {
    if (o.sensor != "rgbd" || o.object_only || o.frame != "camera" || !o.out.empty())
      throw Error("--bag writes the RGB-D frames of the scene as a driver records them: without --out, "
                  "--sensor stereo, --frame or --object-only");
    simulate_bag(s, session.config, o.bag);
    return 0;
  }
  if (o.out.empty()) throw Error("simulate: give --out DIR (or --bag FILE)");
  progress("uwgrasp simulate: building scene " + s.scene.name);
  const sim::World world(s.scene);
  const auto t0 = std::chrono::steady_clock::now();
  const sim::Frame f = sim::render_rgbd(world, s.world_from_camera, s.render, session.config.seed);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  require_depth(f, s);
  std::optional<sim::StereoFrame> stereo;
  if (o.sensor == "stereo")
    stereo = sim::render_stereo(world, s.world_from_camera, s.render, session.config.seed);

  write_simulation(o, s, f, stereo, session.config);
  const auto path = [&](const char* name) { return (std::filesystem::path(o.out) / name).string(); };
  const int w = f.intrinsics.width, h = f.intrinsics.height;
  std::size_t valid = 0;
  for (const auto d : f.depth) valid += d > 0;
  std::printf("scene %s: %zu objects, %zu triangles, water %s, noise %s\n", s.scene.name.c_str(),
              s.scene.objects.size(), world.triangles(), s.render.water.preset.c_str(),
              s.render.noise.enabled ? "on" : "off");
  std::printf("rendered %dx%d in %.1f ms: %zu points with depth (%.1f %%)\n", w, h, ms, valid,
              100.0 * double(valid) / double(f.depth.size()));
  std::printf("wrote %s: cloud.pcd rgb.png depth.png labels.png truth.yaml config.yaml%s%s\n",
              o.out.c_str(), stereo ? " left.png right.png stereo.yaml" : "", s.render.port ? " port.yaml" : "");
  std::printf("detect on it with: uwgrasp detect %s --config %s\n", path("cloud.pcd").c_str(),
              path("config.yaml").c_str());
  return 0;
}
}  // namespace

void add_simulate_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners) {
  auto* cmd = app.add_subcommand("simulate", "Render a scene with the virtual underwater camera");
  auto o = std::make_shared<SimulateOptions>();
  cmd->add_option("--scene", o->scene, "Built-in scene (barbell, ring, cross, thesis, several) or a scene .yaml")
      ->required();
  cmd->add_option("--water", o->water, "Water preset (default: the scene's, else sim.water)")
      ->check(CLI::IsMember({"clear", "coastal", "turbid"}));
  cmd->add_option("--sensor", o->sensor, "rgbd, or stereo (also writes left/right images)")
      ->check(CLI::IsMember({"rgbd", "stereo"}));
  cmd->add_option("--out", o->out, "Output directory");
  cmd->add_option("--bag", o->bag.bag, "Write the frames as a rosbag instead (cloud, images, camera_info, "
                                       "tf, imu; ROS builds only)");
  cmd->add_option("--frames", o->bag.frames, "Frames in the bag (noise seeds seed, seed+1, ...)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--rate", o->bag.rate, "Frame rate of the bag, Hz")->check(CLI::PositiveNumber);
  cmd->add_option("--port", o->port, "The cameras behind this flat port (a port .yaml: distance, thickness, "
                                     "n_air, n_glass, n_water)");
  cmd->add_option("--frame", o->frame, "cloud.pcd in the camera optical frame (default) or in the "
                                       "scene's world frame with the camera pose as its VIEWPOINT")
      ->check(CLI::IsMember({"camera", "world"}));
  cmd->add_flag("--object-only", o->object_only, "cloud.pcd holds only the object of interest's points "
                                                 "(unorganised), as segmented-out clouds do");
  add_common(*cmd, o->common);
  runners.emplace_back(cmd, [o] { return run_simulate(*o); });
}

}  // namespace uwgrasp::app
