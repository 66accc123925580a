#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "objects.hpp"
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
  EXPECT_LT((q.toRotationMatrix().col(0) - a).norm(), 1e-6);  // poses are float inside
  std::size_t rejected = 0;
  for (const auto& [k, v] : j["counts"]["rejected"].items()) rejected += v.get<std::size_t>();
  EXPECT_EQ(rejected + j["counts"]["feasible"].get<std::size_t>(), j["counts"]["candidates"].get<std::size_t>());
}

}  // namespace uwgrasp::io
