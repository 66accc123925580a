// The engine side of the ROS bridge (C++20): frame conventions against uwgrasp's own, and the
// Engine giving exactly what grasp::detect gives.
#include <gtest/gtest.h>

#include <numbers>

#include "engine.hpp"
#include "engine_config.hpp"
#include "fixtures/objects.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/sim/scene.hpp"

namespace uwgrasp_ros {
namespace {

using uwgrasp::Pose;
namespace sim = uwgrasp::sim;

// The simulator's convention (sim/scene.cpp): a vehicle with roll/pitch/yaw in a z-up world has
// its Fossen body at Rx(pi) * R(rpy); its ROS (x forward, y left, z up) body is that times Rx(pi).
TEST(RosBridge, RollAndPitchFromAnImuMatchTheVehicles) {
  for (const Eigen::Vector3d& rpy : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.2, -0.1, 0.7),
                                    Eigen::Vector3d(-0.4, 0.3, -2.5), Eigen::Vector3d(0.05, 0.6, 3.0)}) {
    const Eigen::Matrix3d rx = Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const Eigen::Quaterniond q(rx * uwgrasp::quat_from_rpy(rpy).toRotationMatrix() * rx);
    const auto rp = roll_pitch_from({q.x(), q.y(), q.z(), q.w()});
    EXPECT_NEAR(rp[0], rpy.x(), 1e-9);
    EXPECT_NEAR(rp[1], rpy.y(), 1e-9);
  }
  EXPECT_THROW(roll_pitch_from({0, 0, 0, 0}), uwgrasp::Error);
  EXPECT_THROW(roll_pitch_from({0, 0, std::nan(""), 1}), uwgrasp::Error);
}

TEST(RosBridge, MountFromTfInvertsBodyFromCamera) {
  for (const uwgrasp::Mount& m : {uwgrasp::Mount{{0.2, 0, 0}, {0, -0.6, 0}}, uwgrasp::Mount{{0.1, -0.05, 0.12}, {0.1, 0.2, -0.3}}}) {
    // tf holds the optical frame in the ROS body: T_ros,C = Rx(pi) * T_B,C.
    const Pose T_rosC = uwgrasp::make_pose({0, 0, 0}, Eigen::Quaterniond(0, 1, 0, 0)) * uwgrasp::body_from_camera(m);
    const MountRpy got = mount_from(pose7(T_rosC));
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(got.position[k], m.position[k], 1e-12);
      EXPECT_NEAR(got.rpy[k], m.rpy[k], 1e-9);
    }
  }
}

TEST(RosBridge, ComposeAndInverseAreRigidTransforms) {
  const Pose A = uwgrasp::make_pose({1, 2, 3}, uwgrasp::quat_from_rpy(0.1, 0.2, 0.3));
  const Pose B = uwgrasp::make_pose({-1, 0.5, 2}, uwgrasp::quat_from_rpy(-0.3, 0.4, 1.2));
  const Pose7 ab = compose(pose7(A), pose7(B)), id = compose(pose7(A), inverse(pose7(A)));
  const Pose AB = A * B;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(ab.p[k], AB.translation()[k], 1e-12);
    EXPECT_NEAR(id.p[k], 0.0, 1e-12);
  }
  EXPECT_NEAR(std::abs(id.q[3]), 1.0, 1e-12);
}

TEST(RosBridge, EngineGivesWhatTheDetectorGives) {
  const auto obj = uwgrasp::fixtures::render_object(uwgrasp::fixtures::Object::barbell, {}, 4000);
  uwgrasp::io::Config cfg;
  cfg.grasp.frames.camera.rpy = {0, obj.camera_pitch, 0};
  const Engine engine = make_engine(cfg);
  uwgrasp::Cloud cloud = obj.cloud;
  cloud.normals.clear(), cloud.curvature.clear();  // a sensor's cloud: points and colours
  const PlainDetection got = engine.detect(plain_cloud(cloud), {}, "barbell", "test");
  const auto want = uwgrasp::grasp::detect(cloud, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed);
  ASSERT_TRUE(got.warning.empty()) << got.warning;
  ASSERT_EQ(got.grasps.size(), want.result.grasps.size());
  ASSERT_FALSE(got.grasps.empty());
  for (std::size_t i = 0; i < got.grasps.size(); ++i) {
    const Pose T = uwgrasp::grasp::camera_from_gripper(want.result.grasps[i], want.result.frames);
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(got.grasps[i].pose.p[k], T.translation()[k]);
    EXPECT_DOUBLE_EQ(got.grasps[i].score, want.result.grasps[i].scores.total);
    EXPECT_EQ(got.grasps[i].edges.size(), 36u);  // fingers and palm, 12 edges each
  }
  EXPECT_NE(got.json.find("\"grasps\""), std::string::npos);
}

// A node's Stream (the frames' buffers, reused) over clouds of different sizes and a bad one:
// each frame's detection is the one a fresh call gives.
TEST(RosBridge, EngineThroughAStreamGivesWhatItGivesAlone) {
  const auto near = uwgrasp::fixtures::render_object(uwgrasp::fixtures::Object::barbell, {}, 4000);
  const auto far =
      uwgrasp::fixtures::render_object(uwgrasp::fixtures::Object::barbell, {0.9, 1.0, 0.8}, 2500);
  uwgrasp::io::Config cfg;
  cfg.grasp.frames.camera.rpy = {0, near.camera_pitch, 0};
  const Engine engine = make_engine(cfg);
  PlainCloud bad;
  bad.width = 1;
  bad.xyz = {std::nanf(""), 0, 1};
  const PlainCloud a = plain_cloud(near.cloud), b = plain_cloud(far.cloud);
  Stream stream;
  for (const PlainCloud* c : std::vector<const PlainCloud*>{&a, &b, &bad, &a}) {
    if (c == &bad) {
      EXPECT_THROW(engine.detect(bad, {}, "x", "t", stream), uwgrasp::Error);
      continue;
    }
    const PlainDetection got = engine.detect(*c, {}, "barbell", "test", stream);
    const PlainDetection want = engine.detect(*c, {}, "barbell", "test");
    ASSERT_TRUE(got.warning.empty()) << (c == &a ? "near: " : "far: ") << got.warning;
    ASSERT_FALSE(got.grasps.empty());
    EXPECT_EQ(got.object_xyz, want.object_xyz);
    EXPECT_EQ(got.candidates, want.candidates);
    EXPECT_EQ(got.feasible, want.feasible);
    ASSERT_EQ(got.grasps.size(), want.grasps.size());
    for (std::size_t i = 0; i < got.grasps.size(); ++i) {
      EXPECT_EQ(got.grasps[i].pose.p, want.grasps[i].pose.p);
      EXPECT_EQ(got.grasps[i].pose.q, want.grasps[i].pose.q);
      EXPECT_EQ(got.grasps[i].score, want.grasps[i].score);
    }
  }
}

// The node's and the bag reader's path: a frame written in place into a stream's cloud
// (Stream::frame), as from_msg does, detects as the same points in a PlainCloud do: organised or
// not, with colours or not, frames of other sizes in between, and the same errors.
TEST(RosBridge, FramesFilledInPlaceGiveWhatPlainCloudsGive) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  sim::RenderConfig rc;
  rc.noise.enabled = true;
  rc.camera.width = 320, rc.camera.height = 240;
  const PlainCloud organised =
      plain_cloud(sim::render_rgbd(sim::World(scene), sim::camera_pose(scene, {}), rc, 4).cloud);
  const auto obj = uwgrasp::fixtures::render_object(uwgrasp::fixtures::Object::barbell, {}, 4000);
  PlainCloud unorganised = plain_cloud(obj.cloud);
  unorganised.rgb.clear();
  PlainCloud nothing = organised, behind = unorganised;  // no finite point; behind the camera
  for (float& v : nothing.xyz) v = std::nanf("");
  for (std::size_t i = 2; i < behind.xyz.size(); i += 3) behind.xyz[i] = -behind.xyz[i];
  uwgrasp::io::Config cfg;
  cfg.segment.object.by = uwgrasp::segment::ObjectBy::largest;
  const Engine engine = make_engine(cfg);
  Stream stream;
  const auto fill = [&](const PlainCloud& c) {
    const FrameBuffers b = stream.frame(c.width, c.height, !c.rgb.empty());
    std::copy(c.xyz.begin(), c.xyz.end(), b.xyz);
    if (b.rgb) std::copy(c.rgb.begin(), c.rgb.end(), b.rgb);
  };
  std::size_t detected = 0;
  for (const PlainCloud* c : std::vector<const PlainCloud*>{&organised, &unorganised, &nothing,
                                                            &behind, &unorganised, &organised}) {
    fill(*c);
    if (c == &nothing || c == &behind) {
      EXPECT_THROW(engine.detect_frame({}, "x", "t", stream), uwgrasp::Error);
      EXPECT_THROW(engine.detect(*c, {}, "x", "t"), uwgrasp::Error);
      continue;
    }
    const PlainDetection got = engine.detect_frame({}, "frame", "test", stream);
    const PlainDetection want = engine.detect(*c, {}, "frame", "test");
    ASSERT_TRUE(want.warning.empty()) << want.warning;  // a comparison of real results
    EXPECT_EQ(got.warning, want.warning);
    EXPECT_EQ(got.points_in, c->size());
    EXPECT_EQ(got.object_xyz, want.object_xyz);
    EXPECT_EQ(got.candidates, want.candidates);
    EXPECT_EQ(got.feasible, want.feasible);
    ASSERT_EQ(got.grasps.size(), want.grasps.size());
    ASSERT_FALSE(got.grasps.empty());
    for (std::size_t i = 0; i < got.grasps.size(); ++i) {
      EXPECT_EQ(got.grasps[i].pose.p, want.grasps[i].pose.p);
      EXPECT_EQ(got.grasps[i].pose.q, want.grasps[i].pose.q);
      EXPECT_EQ(got.grasps[i].score, want.grasps[i].score);
    }
    ++detected;
  }
  EXPECT_EQ(detected, 4u);
  EXPECT_EQ(stream.frame(0, 0, true).xyz, nullptr);  // an empty frame has nowhere to write
}

TEST(RosBridge, CloudsThatCannotBeInACameraFrameAreErrors) {
  const Engine engine("", {});
  PlainCloud behind;
  behind.width = 3;
  behind.xyz = {0, 0, -1, 0.1f, 0, -1.2f, 0, 0.1f, -0.9f};
  EXPECT_THROW(engine.detect(behind, {}, "x", "t"), uwgrasp::Error);
  PlainCloud nan;
  nan.width = 1;
  nan.xyz = {std::nanf(""), 0, 1};
  EXPECT_THROW(engine.detect(nan, {}, "x", "t"), uwgrasp::Error);
  PlainCloud few;
  few.width = 2;
  few.xyz = {0, 0, 1, 0.01f, 0, 1};
  EXPECT_FALSE(engine.detect(few, {}, "x", "t").warning.empty());  // a good cloud, nothing to grasp
  EXPECT_THROW(Engine("", {"grasp.nonsense=1"}), uwgrasp::Error);
  Engine e("", {});
  EXPECT_THROW(e.update({"segment.nonsense=2"}), uwgrasp::Error);
}

}  // namespace
}  // namespace uwgrasp_ros
