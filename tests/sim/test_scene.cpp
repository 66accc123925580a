// Built-in scenes, scene files and truth.yaml (io/scene_yaml).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/atomic_file.hpp"
#include "uwgrasp/io/scene_yaml.hpp"
#include "uwgrasp/sim/render.hpp"

namespace {
using namespace uwgrasp;
namespace fs = std::filesystem;

std::string error_of(const std::string& yaml) {
  try {
    io::parse_scene(yaml, "scene.yaml", ".");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, BuiltInScenesShowEveryObjectToTheCamera) {
  const bool data = fs::exists(fs::path(sim::data_dir()) / "meshes");
  if (!data) std::cout << "mesh scenes skipped: no meshes/ in " << sim::data_dir() << "\n";
  for (const auto& name : sim::builtin_scene_names()) {
    if (!data && !name.starts_with("barbell") && !name.starts_with("ring") && !name.starts_with("cross") &&
        name != "thesis" && name != "several")
      continue;
    const sim::Scene s = sim::builtin_scene(name);
    const sim::World world(s);
    sim::RenderConfig c;
    c.noise.enabled = false;
    const sim::Frame f = sim::render_rgbd(world, sim::camera_pose(s, Mount{}), c, 1);
    for (std::size_t i = 0; i < s.objects.size(); ++i) {
      std::size_t n = 0;
      for (const auto l : f.labels) n += l == sim::kLabelFirstObject + i;
      EXPECT_GT(n, 300u) << name << " " << s.objects[i].name;
    }
  }
}

TEST(Scene, BarbellKeepsTheThesisIntent) {
  // Bar narrower than the gripper's usable 70 mm, blocks wider (8.1).
  const sim::Scene s = sim::builtin_scene("barbell");
  const auto& parts = s.objects[0].parts;
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_LT(parts[2].shape.size.y(), 0.07);
  EXPECT_GT(parts[0].shape.size.y(), 0.07);
  EXPECT_GT(parts[0].shape.size.x(), 0.07);
}

TEST(SceneFile, ParsesEveryShapeAndPose) {
  const sim::Scene s = io::parse_scene(R"(
name: dock
seafloor: {size: 10, color: [100, 100, 90]}
vehicle: {position: [-1, 0, 0.6], rpy: [0, 0, 0.1]}
camera_mount: {position: [0.2, 0, 0], rpy: [0, -0.5, 0]}
water: {preset: coastal, snow_density: 10}
objects:
  - name: a
    interest: true
    pose: {position: [0, 0, 0], orientation_xyzw: [0, 0, 0.7071068, 0.7071068]}
    parts:
      - {shape: box, size: [0.1, 0.2, 0.3]}
      - {shape: box, size: [0.36, 0.27, 0.005], checker: {cols: 9, rows: 6, square: 0.03}}
      - {shape: cylinder, radius: 0.01, length: 0.2, pose: {position: [0, 0, 0.3]}}
      - {shape: sphere, radius: 0.05}
      - {shape: torus, major: 0.1, radius: 0.01}
)", "dock.yaml", ".");
  EXPECT_EQ(s.name, "dock");
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].parts.size(), 5u);
  EXPECT_EQ(s.objects[0].parts[1].shape.checker.cols, 9);
  EXPECT_EQ(s.objects[0].parts[1].shape.checker.rows, 6);
  EXPECT_DOUBLE_EQ(s.objects[0].parts[1].shape.checker.square, 0.03);
  EXPECT_EQ(s.objects[0].parts[0].shape.checker.square, 0.0);
  EXPECT_NEAR(s.vehicle.rpy.z(), 0.1, 1e-12);
  ASSERT_TRUE(s.water.has_value());
  EXPECT_EQ(s.water->preset, "coastal");
  EXPECT_EQ(s.water->snow_density, 10.0);
  EXPECT_NEAR(s.objects[0].pose.linear()(1, 0), 1.0, 1e-6);  // 90 degrees about z
}

TEST(SceneFile, BadInputNamesTheKey) {
  EXPECT_NE(error_of("objects: [{name: a, parts: [{shape: box, sizes: [1, 1, 1]}]}]").find("objects[0].parts[0].sizes"), std::string::npos);
  EXPECT_NE(error_of("objects: [{name: a, parts: [{shape: cone, radius: 1}]}]").find("unknown shape"), std::string::npos);
  EXPECT_NE(error_of("objects: [{name: a, parts: [{shape: box, size: [1, -1, 1]}]}]").find("size[1]"), std::string::npos);
  EXPECT_NE(error_of("water: {veiling: [0.1, 2, 0.1]}").find("water.veiling[1]"), std::string::npos);
  EXPECT_NE(error_of("water: {preset: muddy}").find("muddy"), std::string::npos);
  EXPECT_NE(error_of("objects: [{name: a, parts: [{shape: torus, major: 0.01, radius: 0.1}]}]").find("major"), std::string::npos);
  EXPECT_NE(error_of("objects: [{name: a, parts: []}]").find("parts"), std::string::npos);
  EXPECT_NE(error_of("objects: [{name: a, parts: [{shape: sphere, radius: 1, checker: {cols: 9, rows: 6, square: 0.03}}]}]")
                .find("parts[0].checker"), std::string::npos);
  EXPECT_NE(error_of("objects: [{name: a, parts: [{shape: box, size: [1,1,1], checker: {cols: 9, rows: 6}}]}]")
                .find("checker.square"), std::string::npos);
  EXPECT_NE(error_of("objects: [{name: a, parts: [{shape: box, size: [1,1,1]}]}, {name: a, parts: [{shape: box, size: [1,1,1]}]}]").find("duplicate"), std::string::npos);
  EXPECT_NE(error_of("seafloor: {enabled: false}").find("nothing to see"), std::string::npos);
  EXPECT_NE(error_of("objects: [{name: a, parts: [{shape: box, size: [1").find("not valid YAML"), std::string::npos);
  EXPECT_THROW(io::load_scene("/nonexistent/scene.yaml"), Error);
  EXPECT_THROW(io::load_scene("atlantis"), Error);
}

TEST(SceneFile, MissingMeshFailsWhenTheWorldIsBuilt) {
  const sim::Scene s = io::parse_scene("objects: [{name: a, parts: [{shape: mesh, file: no_such.dae}]}]", "x.yaml", "/tmp");
  try {
    sim::World w(s);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/tmp/no_such.dae"), std::string::npos) << e.what();
  }
}

TEST(Truth, TruthYamlReadsBackAsTheSameScene) {
  sim::Scene s = sim::builtin_scene("several");
  s.objects[0].parts.push_back({sim::Shape{.size = Eigen::Vector3d(0.36, 0.27, 0.005), .checker = {9, 6, 0.03}}, Pose::Identity()});
  io::TruthInfo t;
  t.world_from_camera = sim::camera_pose(s, Mount{});
  t.camera_mount = *s.camera_mount;
  t.intrinsics = sim::make_intrinsics(t.camera);
  t.water = sim::water_preset("turbid");
  const sim::Scene back = io::parse_scene(io::truth_yaml(s, t), "truth.yaml", ".");
  ASSERT_EQ(back.objects.size(), s.objects.size());
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    EXPECT_EQ(back.objects[i].name, s.objects[i].name);
    EXPECT_EQ(back.objects[i].color, s.objects[i].color);
    EXPECT_EQ(back.objects[i].interest, s.objects[i].interest);
    EXPECT_TRUE(back.objects[i].pose.isApprox(s.objects[i].pose, 1e-12));
    ASSERT_EQ(back.objects[i].parts.size(), s.objects[i].parts.size());
    for (std::size_t j = 0; j < s.objects[i].parts.size(); ++j)
      EXPECT_EQ(back.objects[i].parts[j].shape.checker.cols, s.objects[i].parts[j].shape.checker.cols);
    const sim::Mesh a = sim::object_mesh(s.objects[i]), b = sim::object_mesh(back.objects[i]);
    EXPECT_NEAR(sim::volume(a), sim::volume(b), 1e-12);
  }
  EXPECT_TRUE(back.vehicle.position.isApprox(s.vehicle.position));
  EXPECT_TRUE(back.camera_mount->rpy.isApprox(s.camera_mount->rpy, 1e-12));
  EXPECT_EQ(back.water->attenuation, t.water.attenuation);
}

// load_truth also reads the camera back, and names what is missing.
TEST(Truth, LoadTruthReadsTheCameraAndNamesMissingParts) {
  const sim::Scene s = sim::builtin_scene("barbell");
  io::TruthInfo t;
  t.world_from_camera = sim::camera_pose(s, Mount{});
  t.intrinsics = sim::make_intrinsics(t.camera);
  const auto dir = std::filesystem::temp_directory_path();
  const std::string path = (dir / "uwgrasp_truth_read.yaml").string();
  io::write_text(path, io::truth_yaml(s, t));
  const io::Truth back = io::load_truth(path);
  EXPECT_TRUE(back.info.world_from_camera.isApprox(t.world_from_camera, 1e-12));
  EXPECT_EQ(back.info.intrinsics.width, 640);
  EXPECT_DOUBLE_EQ(back.info.intrinsics.fx, t.intrinsics.fx);
  EXPECT_DOUBLE_EQ(back.info.camera.max_range, 6.0);
  const auto fails_naming = [&](const std::string& text, const std::string& what) {
    io::write_text(path, text);
    try {
      io::load_truth(path);
      ADD_FAILURE() << "expected an Error naming " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  const std::string yaml = io::truth_yaml(s, t);
  fails_naming(yaml.substr(0, yaml.find("camera:")) + yaml.substr(yaml.find("vehicle:")), "camera");
  std::string no_fx = yaml;
  no_fx.erase(no_fx.find("    fx:"), no_fx.find("    fy:") - no_fx.find("    fx:"));
  fails_naming(no_fx, "camera.intrinsics.fx");
  fails_naming("camera: {world_from_camera: {position: [0, 0, 1]}, intrinsics: {width: 64, height: 48, "
               "fx: 50, fy: 50, cx: 32, cy: 24}}\nobjects: [{name: a, parts: [{shape: mesh, file: "
               "/tmp/uwgrasp_no_such_mesh.obj}]}]\n",
               "objects[0].parts[0].file");
  EXPECT_THROW(io::load_truth((dir / "uwgrasp_no_such_truth.yaml").string()), Error);
}

}  // namespace
