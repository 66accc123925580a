#include "holds_scenes.hpp"

#include "uwgrasp/eval/exists.hpp"
#include "uwgrasp/sim/builtin_scenes.hpp"

namespace uwgrasp::holds {

sim::SceneObject solid(const std::string& name, const sim::Shape& shape, const V3& centre) {
  Pose p = Pose::Identity();
  p.translation() = centre;
  return {name, {{shape, Pose::Identity()}}, p, {200, 30, 30}, true};
}

sim::Scene on_floor(const sim::SceneObject& o) {
  sim::Scene s;
  s.name = o.name;
  s.objects = {o};
  s.vehicle = sim::looking_at(o.pose.translation(), 0.7);
  s.camera_mount = sim::tilted_camera();
  return s;
}

Judged detect_and_judge(const sim::Scene& scene, io::Config cfg, std::uint64_t seed, bool search_exists,
                        const std::string& water) {
  const sim::World world(scene);
  sim::RenderConfig rc;
  rc.noise.enabled = !water.empty();
  if (!water.empty()) rc.water = sim::water_preset(water);
  const Pose T_WC = sim::camera_pose(scene, {});
  Judged out;
  out.frame = sim::render_rgbd(world, T_WC, rc, seed);
  cfg.grasp.frames.camera = *scene.camera_mount;
  grasp::given_attitude(cfg.grasp.frames, scene.vehicle.rpy.x(),
                        scene.vehicle.rpy.y());  // an IMU's
  out.detection = grasp::detect(out.frame.cloud, cfg.preprocess, cfg.segment, cfg.grasp, seed);
  const eval::Camera cam{T_WC, out.frame.intrinsics, rc.camera.max_range};
  const grasp::Gripper g = grasp::make_gripper(cfg.grasp.gripper);
  std::vector<Pose> poses;
  for (const auto& k : out.detection.result.grasps)
    poses.push_back(T_WC * grasp::camera_from_gripper(k, out.detection.result.frames));
  eval::SummaryConfig sc;
  sc.top = 10;
  out.evaluation = eval::evaluate(world, cam, g, poses, 0, sc, eval::RobustConfig{}, seed);
  out.exists = search_exists && eval::find_any_grasp(world, cam, g, 0).exists;
  return out;
}

bool top1_holds(const Judged& j) {
  return !j.evaluation.judgements.empty() && j.evaluation.judgements.front().holds(0.4);
}

}  // namespace uwgrasp::holds
