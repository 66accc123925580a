#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "objects.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/grasps_json.hpp"

namespace uwgrasp::io {

namespace {
std::string detect_json(int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const auto obj = fixtures::render_object(fixtures::Object::cross, {}, 20000);
  Config cfg;
  cfg.grasp.frames.camera.rpy.y() = obj.camera_pitch;
  cfg.preprocess.plane.enabled = false;  // the object alone
  const grasp::Detection d = grasp::detect(obj.cloud, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed);
  nlohmann::json j = grasps_to_json(d, cfg, "/some/dir/cross.pcd", "test");
  j.erase("timing_ms");  // wall-clock times are the one thing that differs between runs
  return j.dump(2);
}
}  // namespace

TEST(GraspsJson, FieldsAsSpecifiedAndByteIdenticalAcrossThreadCounts) {
  const std::string one = detect_json(1), two = detect_json(2);
  EXPECT_EQ(one, two);
  const nlohmann::json j = nlohmann::json::parse(one);
  EXPECT_EQ(j["input"], "cross.pcd");
  EXPECT_EQ(j["frame"], "camera_optical");
  EXPECT_EQ(j["seed"], 1);
  EXPECT_TRUE(j["config"]["grasp"]["gripper"].contains("max_aperture"));
  for (const char* k : {"points_in", "points_after_preprocess", "object_points", "candidates", "feasible"})
    EXPECT_TRUE(j["counts"].contains(k)) << k;
  ASSERT_FALSE(j["grasps"].empty());
  const auto& g = j["grasps"][0];
  EXPECT_EQ(g["rank"], 1);
  for (const char* k : {"position", "orientation_xyzw", "approach", "closing", "score", "scores",
                        "inliers", "width", "contacts", "vehicle_pose", "hold_cost"})
    EXPECT_TRUE(g.contains(k)) << k;
  EXPECT_EQ(g["orientation_xyzw"].size(), 4u);
  for (const char* k : {"normal", "orientation", "contact_left", "contact_right", "inliers", "vehicle"})
    EXPECT_TRUE(g["scores"].contains(k)) << k;
  // approach and closing are the columns of the orientation.
  const Eigen::Quaterniond q(g["orientation_xyzw"][3].get<double>(), g["orientation_xyzw"][0].get<double>(),
                             g["orientation_xyzw"][1].get<double>(), g["orientation_xyzw"][2].get<double>());
  const Eigen::Vector3d a(g["approach"][0].get<double>(), g["approach"][1].get<double>(), g["approach"][2].get<double>());
  EXPECT_NEAR(q.norm(), 1.0, 1e-12);
  EXPECT_LT((q.toRotationMatrix().col(0) - a).norm(), 1e-12);
  std::size_t rejected = 0;
  for (const auto& [k, v] : j["counts"]["rejected"].items()) rejected += v.get<std::size_t>();
  EXPECT_EQ(rejected + j["counts"]["feasible"].get<std::size_t>(), j["counts"]["candidates"].get<std::size_t>());
}

namespace {
// ctest runs each test in its own process, several at once: the process id keeps two tests
// from writing the same file (GraspList.BadFieldsAreNamed read a neighbour's file once). The
// files are removed when the process ends.
struct TmpFiles {
  std::vector<std::string> paths;
  ~TmpFiles() {
    std::error_code ignored;
    for (const auto& p : paths) std::filesystem::remove(p, ignored);
  }
};
std::string write_tmp(const std::string& name, const std::string& text) {
  static TmpFiles written;
  const std::string path =
      (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name)).string();
  std::ofstream(path) << text;
  if (std::find(written.paths.begin(), written.paths.end(), path) == written.paths.end()) written.paths.push_back(path);
  return path;
}
std::string list_error(const std::string& text, const std::string& object = "") {
  try {
    read_grasp_list(write_tmp("uwgrasp_list.json", text), object);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

// Another detector's file: only the documented fields, extra ones ignored, no config.
TEST(GraspList, ReadsAnyDetectorsFileOrderedByScore) {
  const GraspList l = read_grasp_list(
      write_tmp("uwgrasp_list.json",
                R"({"detector": "other", "grasps": [
                     {"position": [0, 0, 1], "orientation_xyzw": [0, 0, 0, 1], "score": 0.2, "extra": 3},
                     {"position": [0, 0, 2], "orientation_xyzw": [0, 0, 0.7071068, 0.7071068], "score": 0.9}]})"),
      "");
  ASSERT_EQ(l.grasps.size(), 2u);
  EXPECT_EQ(l.frame, "camera_optical");
  EXPECT_FALSE(l.gripper_from_file);
  EXPECT_DOUBLE_EQ(l.grasps[0].score, 0.9);
  EXPECT_EQ(l.grasps[0].rank, 2u);
  EXPECT_NEAR(l.grasps[0].pose.translation().z(), 2.0, 1e-12);
  EXPECT_NEAR(l.grasps[0].pose.linear()(1, 0), 1.0, 1e-6);  // 90 degrees about z
  EXPECT_EQ(l.grasps[1].rank, 1u);
}

TEST(GraspList, GripperFromTheConfigAndDemoObjects) {
  const GraspList l = read_grasp_list(
      write_tmp("uwgrasp_list.json",
                R"({"objects": [{"name": "ring", "config": {"grasp": {"gripper": {"max_aperture": 0.12}}},
                                 "grasps": []},
                                {"name": "cross", "grasps": []}]})"),
      "ring");
  EXPECT_TRUE(l.gripper_from_file);
  EXPECT_FLOAT_EQ(l.gripper.max_aperture, 0.12f);
  EXPECT_EQ(l.object, "ring");
  EXPECT_NE(list_error(R"({"objects": [{"name": "ring", "grasps": []}]})").find("--object"), std::string::npos);
  EXPECT_NE(list_error(R"({"objects": [{"name": "ring", "grasps": []}]})", "anchor").find("anchor"), std::string::npos);
}

TEST(GraspList, BadFieldsAreNamed) {
  EXPECT_NE(list_error(R"({"grasps": [{"position": [0, 0], "orientation_xyzw": [0, 0, 0, 1], "score": 1}]})")
                .find("grasps[0].position"), std::string::npos);
  EXPECT_NE(list_error(R"({"grasps": [{"position": [0, 0, 1], "orientation_xyzw": [0, 0, 0, 1]}]})")
                .find("grasps[0].score"), std::string::npos);
  EXPECT_NE(list_error(R"({"grasps": [{"position": [0, 0, 1], "orientation_xyzw": [0, 0, 0, 1.2], "score": 1}]})")
                .find("not a unit quaternion"), std::string::npos);
  EXPECT_NE(list_error(R"({"frame": "base_link", "grasps": []})").find("frame"), std::string::npos);
  EXPECT_NE(list_error(R"({"config": {"grasp": {"gripper": {"max_aperture": -1}}}, "grasps": []})")
                .find("grasp.gripper.max_aperture"), std::string::npos);
  EXPECT_NE(list_error("{").find("not valid JSON"), std::string::npos);
  EXPECT_NE(list_error(R"({"nothing": 1})").find("grasps"), std::string::npos);
}

}  // namespace uwgrasp::io
