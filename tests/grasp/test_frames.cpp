// grasp/frames: the capture attitude from the seafloor plane (level_from_floor) against the
// attitude a level floor was seen from, and a whole detection on a simulated frame seen from a
// pitched camera with no attitude given.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/grasps_json.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/sim/scene.hpp"

namespace {
using namespace uwgrasp;
using grasp::FrameConfig;

constexpr double kDeg = std::numbers::pi / 180.0;

// The plane z_L = h (a level floor h below the camera) as the camera of `f` sees it: n.p + d = 0
// in the camera frame, scaled and signed at random as a plane fit may give it.
Eigen::Vector4f floor_in_camera(const FrameConfig& f, double h, double scale) {
  const Pose T = grasp::make_frames(f).level_from_camera;  // p_L = R p_C + t
  const Eigen::Vector3d n = T.linear().transpose() * Eigen::Vector3d::UnitZ();
  const double d = T.translation().z() - h;
  return (scale * Eigen::Vector4d(n.x(), n.y(), n.z(), d)).cast<float>();
}

// Roll and pitch within +-50 degrees, cameras mounted ahead, pitched down or looking straight
// down: the floor gives back the attitude it was seen from, and floor points then lie level.
TEST(FloorAttitude, RecoversTheAttitudeALevelFloorWasSeenFrom) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-50 * kDeg, 50 * kDeg), mount(-90 * kDeg, 0.0),
      scale(0.2, 3.0);
  for (int trial = 0; trial < 200; ++trial) {
    FrameConfig seen;
    seen.camera.rpy = {0.3 * angle(rng), mount(rng), 0.2 * angle(rng)};
    seen.capture_roll = angle(rng), seen.capture_pitch = angle(rng);
    const double sign = trial % 2 ? 1.0 : -1.0;
    const Eigen::Vector4f plane = floor_in_camera(seen, 1.5, sign * scale(rng));
    FrameConfig given = seen;  // the mount is known, the attitude is not
    given.capture_roll = given.capture_pitch = 0.0;
    const auto a = grasp::attitude_from_floor(plane, given, std::numbers::pi);
    ASSERT_TRUE(a.has_value()) << trial;
    EXPECT_NEAR(a->roll, seen.capture_roll, 1e-5) << trial;
    EXPECT_NEAR(a->pitch, seen.capture_pitch, 1e-5) << trial;
    given.capture_roll = a->roll, given.capture_pitch = a->pitch;
    // Floor points (z = 1.5 m in the L they were seen in) all at one height in the recovered L.
    const Pose seen_T = grasp::make_frames(seen).level_from_camera,
               T = grasp::make_frames(given).level_from_camera;
    const double z0 = (T * (seen_T.inverse() * Eigen::Vector3d(0.0, 0.0, 1.5))).z();
    for (const Eigen::Vector3d& on :
         {Eigen::Vector3d(2.0, -1.0, 1.5), Eigen::Vector3d(-3.0, 4.0, 1.5)})
      EXPECT_NEAR((T * (seen_T.inverse() * on)).z(), z0, 1e-6) << trial;
  }
}

// The tilt from the configured level, and what is not a floor: a wall (90 degrees), a plane
// through the camera, no normal.
TEST(FloorAttitude, RefusesWallsAndDegeneratePlanes) {
  FrameConfig level;  // camera ahead, level
  FrameConfig pitched = level;
  pitched.capture_pitch = -37.0 * kDeg;  // nose down, as a camera at a table
  const Eigen::Vector4f table = floor_in_camera(pitched, 0.8, 1.0);
  EXPECT_NEAR(*grasp::floor_tilt(table, level), 37.0 * kDeg, 1e-5);
  const auto a = grasp::attitude_from_floor(table, level);
  ASSERT_TRUE(a.has_value());
  EXPECT_NEAR(a->pitch, -37.0 * kDeg, 1e-5);
  EXPECT_NEAR(a->roll, 0.0, 1e-5);
  const Eigen::Vector4f wall(0.0f, 0.0f, -1.0f, 2.0f);  // facing the camera 2 m ahead
  EXPECT_NEAR(*grasp::floor_tilt(wall, level), 90.0 * kDeg, 1e-5);
  EXPECT_FALSE(grasp::attitude_from_floor(wall, level).has_value());
  EXPECT_FALSE(grasp::attitude_from_floor(Eigen::Vector4f(0, -1, 0, 0), level).has_value());
  EXPECT_FALSE(grasp::attitude_from_floor(Eigen::Vector4f(0, 0, 0, 1), level).has_value());
  EXPECT_FALSE(grasp::attitude_from_floor(Eigen::Vector4f(NAN, -1, 0, 1), level).has_value());
}

// "auto" levels from the floor only while no attitude is given: the defaults (both zero) say
// nothing, a measured attitude (given_attitude, even a level one) or a configured one does.
TEST(FloorAttitude, AutoLevelsFromTheFloorOnlyWithNoAttitudeGiven) {
  using L = FrameConfig::Level;
  FrameConfig f;
  EXPECT_EQ(f.level_from_floor, L::automatic);
  EXPECT_TRUE(grasp::levels_from_floor(f));
  FrameConfig configured = f;
  configured.capture_pitch = 0.1;
  EXPECT_FALSE(grasp::levels_from_floor(configured));
  FrameConfig measured = f;
  grasp::given_attitude(measured, 0.0, 0.0);
  EXPECT_FALSE(grasp::levels_from_floor(measured));
  EXPECT_EQ(measured.level_from_floor, L::attitude);
  FrameConfig always = f;
  always.level_from_floor = L::floor;
  grasp::given_attitude(always, 0.2, -0.1);  // an explicit choice outranks a measurement
  EXPECT_TRUE(grasp::levels_from_floor(always));
  EXPECT_DOUBLE_EQ(always.capture_roll, 0.2);
  EXPECT_DOUBLE_EQ(always.capture_pitch, -0.1);
  FrameConfig never = f;
  never.level_from_floor = L::attitude;
  EXPECT_FALSE(grasp::levels_from_floor(never));
}

// The thesis scene from the simulator's pitched camera, with the depth camera's noise: given the
// mount as if level and no attitude, the detection takes the camera's pitch from the seafloor
// plane it fitted, and finds its grasps in (nearly) the true L.
TEST(FloorAttitude, ADetectionFindsThePitchOfTheCameraThatSawIt) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const Mount truth = scene.camera_mount.value_or(Mount{});
  ASSERT_LT(truth.rpy.y(), -0.3) << "the scene's camera looks down";
  sim::RenderConfig rc;
  rc.noise.enabled = true;
  const Cloud frame = sim::render_rgbd(sim::World(scene), sim::camera_pose(scene, {}), rc, 5).cloud;
  io::Config cfg;
  cfg.segment.object.by = segment::ObjectBy::largest;
  cfg.grasp.frames.camera = {truth.position, Eigen::Vector3d::Zero()};
  cfg.grasp.frames.level_from_floor = FrameConfig::Level::floor;
  const grasp::Detection d = grasp::detect(frame, cfg.preprocess, cfg.segment, cfg.grasp, 1);
  ASSERT_TRUE(d.floor_attitude.has_value());
  EXPECT_NEAR(d.floor_attitude->pitch, truth.rpy.y(), 1.0 * kDeg);
  EXPECT_NEAR(d.floor_attitude->roll, truth.rpy.x(), 1.0 * kDeg);
  FrameConfig right = cfg.grasp.frames;
  right.camera = truth;
  const Eigen::Matrix3d want = grasp::make_frames(right).level_from_camera.linear();
  const Eigen::Matrix3d got = d.result.frames.level_from_camera.linear();
  EXPECT_LT(Eigen::AngleAxisd(want.transpose() * got).angle(), 1.0 * kDeg);
  // grasps.json's config is the one the grasps were found with.
  const nlohmann::json j = io::grasps_to_json(d, cfg, "frame.pcd", "test");
  EXPECT_DOUBLE_EQ(j["config"]["grasp"]["frames"]["capture_pitch"].get<double>(),
                   d.floor_attitude->pitch);
  EXPECT_DOUBLE_EQ(j["config"]["grasp"]["frames"]["capture_roll"].get<double>(),
                   d.floor_attitude->roll);
  // grasps.json's config reproduces these frames when read back: the attitude, kept as given.
  EXPECT_EQ(j["config"]["grasp"]["frames"]["level_from_floor"], "false");
  // The default, "auto", given no attitude, finds the same.
  cfg.grasp.frames.level_from_floor = FrameConfig::Level::automatic;
  const grasp::Detection automatic =
      grasp::detect(frame, cfg.preprocess, cfg.segment, cfg.grasp, 1);
  ASSERT_TRUE(automatic.floor_attitude.has_value());
  EXPECT_EQ(automatic.floor_attitude->pitch, d.floor_attitude->pitch);
  EXPECT_EQ(automatic.floor_attitude->roll, d.floor_attitude->roll);
  // Off, the same frame is taken as level: its L is the pitch away from the truth.
  cfg.grasp.frames.level_from_floor = FrameConfig::Level::attitude;
  const grasp::Detection as_given = grasp::detect(frame, cfg.preprocess, cfg.segment, cfg.grasp, 1);
  EXPECT_FALSE(as_given.floor_attitude.has_value());
  EXPECT_NEAR(
      Eigen::AngleAxisd(want.transpose() * as_given.result.frames.level_from_camera.linear())
          .angle(),
      std::abs(truth.rpy.y()), 1e-6);
}

}  // namespace
