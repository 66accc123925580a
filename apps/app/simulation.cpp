#include "app/simulation.hpp"

#include <cerrno>
#include <fstream>

#include "app/common.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/io/atomic_file.hpp"

namespace uwgrasp::app {

Simulation make_simulation(const io::Config& cfg, const std::string& scene, const std::string& water) {
  Simulation s;
  s.scene = io::load_scene(scene);
  s.render.camera = cfg.sim.camera;
  s.render.noise = cfg.sim.noise;
  s.render.water = !water.empty()     ? sim::water_preset(water)
                   : s.scene.water    ? *s.scene.water
                                      : sim::water_preset(cfg.sim.water);
  sim::check_camera(s.render.camera);
  sim::check_water(s.render.water);
  sim::check_noise(s.render.noise);
  s.render.port = s.scene.port;
  if (s.render.port) check_port(*s.render.port);
  s.mount = s.scene.camera_mount.value_or(cfg.grasp.frames.camera);
  s.world_from_camera = sim::camera_pose(s.scene, s.mount);
  return s;
}

void use_simulation_frames(io::Config& cfg, const Simulation& s) {
  cfg.grasp.frames.camera = s.mount;
  grasp::given_attitude(cfg.grasp.frames, s.scene.vehicle.rpy.x(), s.scene.vehicle.rpy.y());
}

void require_depth(const sim::Frame& f, const Simulation& s) {
  bool any = false;  // depth on the seafloor or an object (marine snow alone does not count)
  for (std::size_t i = 0; i < f.depth.size() && !any; ++i)
    any = f.depth[i] > 0 && f.labels[i] != sim::kLabelSnow;
  if (!any)
    throw Error("scene " + s.scene.name + ": the camera sees nothing within " +
                std::to_string(s.render.camera.max_range) + " m (check vehicle pose and camera mount)");
}

io::TruthInfo truth_info(const Simulation& s, const sim::Intrinsics& k, const std::string& sensor,
                         std::uint64_t seed) {
  io::TruthInfo t;
  t.sensor = sensor;
  t.seed = seed;
  t.world_from_camera = s.world_from_camera;
  t.camera_mount = s.mount;
  t.intrinsics = k;
  t.camera = s.render.camera;
  t.water = s.render.water;
  t.noise = s.render.noise;
  return t;
}

Eigen::Vector3d visible_centroid(const sim::Frame& f, const Simulation& s, std::size_t i) {
  const auto label = static_cast<std::uint16_t>(sim::kLabelFirstObject + i);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (std::size_t p = 0; p < f.labels.size(); ++p)
    if (f.labels[p] == label && f.cloud.points[p].allFinite()) sum += f.cloud.points[p].cast<double>(), ++n;
  if (n == 0) throw Error("scene " + s.scene.name + ": object " + s.scene.objects.at(i).name + " is not in view");
  return sum / double(n);
}

io::Config object_config(const Simulation& s, const sim::Frame& f, std::size_t i,
                         const std::vector<std::string>& sets, std::uint64_t seed) {
  const std::string& name = s.scene.objects.at(i).name;
  io::Config cfg = io::load_config(preset_path("thesis_" + (name == "ring" ? "circle" : name) + ".yaml"), sets);
  return pointed_at(std::move(cfg), s, f, i, seed);
}

io::Config pointed_at(io::Config cfg, const Simulation& s, const sim::Frame& f, std::size_t i,
                      std::uint64_t seed) {
  cfg.seed = seed;
  use_simulation_frames(cfg, s);
  cfg.segment.object.by = segment::ObjectBy::point;
  cfg.segment.object.point = visible_centroid(f, s, i);
  return cfg;
}

viz::Wire gripper_wire(const Pose& T, const grasp::Gripper& g, bool body) {
  viz::Wire w;
  w.segments = grasp::gripper_edges(T, g, body);
  return w;
}

std::vector<viz::Wire> grasp_wires(const std::vector<grasp::Grasp>& grasps, const grasp::Frames& f,
                                   const grasp::GripperConfig& gripper, bool body) {
  const grasp::Gripper g = grasp::make_gripper(gripper);
  std::vector<viz::Wire> out;
  for (const auto& gr : grasps) {
    viz::Wire w = gripper_wire(grasp::camera_from_gripper(gr, f), g, body);
    w.value = gr.scores.total;
    out.push_back(std::move(w));
  }
  return out;
}

vehicle::ApproachTask approach_task(const Pose& level_from_vehicle, const Pose& level_from_gripper,
                                    const io::Config& cfg) {
  vehicle::ApproachTask t;
  t.start.attitude = quat_from_rpy(cfg.grasp.frames.capture_roll, cfg.grasp.frames.capture_pitch, 0.0);
  t.goal = level_from_vehicle.translation();
  t.goal_attitude = Eigen::Quaterniond(level_from_vehicle.linear());
  t.approach_axis = level_from_gripper.linear().col(0).normalized();
  t.standoff = cfg.grasp.reach.standoff;
  return t;
}

void write_png(const std::string& path, const cv::Mat& image) {
  const std::vector<std::uint8_t> bytes = viz::encode_png(image);
  io::write_atomically(path, [&](const std::string& tmp) {
    errno = 0;
    std::ofstream out(tmp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.close();  // the last bytes reach the file here: a full disk shows now
    if (!out) throw Error(path + ": cannot write" + io::reason());
  });
}

}  // namespace uwgrasp::app
