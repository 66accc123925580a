// The round trip a user makes: simulate a scene, detect grasps on its cloud, write grasps.json
// in the camera frame, read it back and judge it in the world. With the perfect sensor in clear
// water the contacts the detector wrote on the camera's points lie on the true mesh; those it
// predicted on the unseen part lie within the model's voxels of it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "uwgrasp/eval/evaluate.hpp"
#include "uwgrasp/io/grasps_json.hpp"
#include "uwgrasp/io/scene_yaml.hpp"
#include "uwgrasp/sim/render.hpp"

namespace {
using namespace uwgrasp;

struct Detected {
  sim::Scene scene;
  sim::Frame frame;
  std::string json_path;
};

Detected detect_on(const std::string& scene_name) {
  Detected out;
  out.scene = sim::builtin_scene(scene_name);
  const sim::World world(out.scene);
  sim::RenderConfig rc;
  rc.noise.enabled = false;  // the perfect sensor in clear water (the default water)
  const Pose T_WC = sim::camera_pose(out.scene, {});
  out.frame = sim::render_rgbd(world, T_WC, rc, 1);
  io::Config cfg;
  cfg.grasp.frames.camera = *out.scene.camera_mount;
  grasp::given_attitude(cfg.grasp.frames, out.scene.vehicle.rpy.x(), out.scene.vehicle.rpy.y());
  const grasp::Detection d = grasp::detect(out.frame.cloud, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed);
  out.json_path = (std::filesystem::temp_directory_path() / std::string("uwgrasp_roundtrip_").append(scene_name).append(".json")).string();
  io::write_json(out.json_path, io::grasps_to_json(d, cfg, "cloud.pcd", "test"));
  return out;
}

TEST(DetectThenJudge, ContactsFromGraspsJsonLieOnTheTrueMesh) {
  std::size_t checked = 0;  // contacts on the camera's points
  for (const std::string name : {"barbell", "ring", "cross"}) {
    const Detected d = detect_on(name);
    const sim::World world(d.scene);
    std::ifstream in(d.json_path);
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_FALSE(j["grasps"].empty()) << name;
    for (const auto& g : j["grasps"])
      for (int side = 0; side < 2; ++side) {
        const auto& c = g["contacts"][side];
        const Eigen::Vector3d p_c(c[0].get<double>(), c[1].get<double>(), c[2].get<double>());
        const Eigen::Vector3d p_w = d.frame.world_from_camera * p_c;
        const sim::NearestSurface n = sim::nearest_surface(world, p_w, 0.05);
        ASSERT_EQ(n.object, 0) << name;
        const bool seen = g["contact_seen"][side].get<bool>();
        EXPECT_LT(n.distance, seen ? 0.001 : 0.01) << name << " contact " << p_w.transpose();
        checked += seen;
      }
  }
  EXPECT_GE(checked, 10u);
}

// The grasps read back and put in the world through the camera pose are judged there: every
// one is in reach of the object (its closing region touches the object, or a part hits it).
TEST(DetectThenJudge, GraspsReadBackAreJudgedAtTheObject) {
  const Detected d = detect_on("barbell");
  const io::GraspList list = io::read_grasp_list(d.json_path, "");
  ASSERT_FALSE(list.grasps.empty());
  EXPECT_TRUE(list.gripper_from_file);
  const sim::World world(d.scene);
  const eval::Camera cam{d.frame.world_from_camera, d.frame.intrinsics, 6.0};
  std::vector<Pose> poses;
  for (const auto& g : list.grasps) poses.push_back(cam.world_from_camera * g.pose);
  const eval::Evaluation e = eval::evaluate(world, cam, grasp::make_gripper(list.gripper), poses, 0, {}, {}, 1);
  ASSERT_EQ(e.judgements.size(), std::min<std::size_t>(10, poses.size()));
  for (const auto& jg : e.judgements) {
    EXPECT_NE(jg.verdict, eval::Verdict::miss);
    EXPECT_NE(jg.verdict, eval::Verdict::other_object);
  }
  EXPECT_TRUE(std::isfinite(e.robust_top1));
}

}  // namespace
