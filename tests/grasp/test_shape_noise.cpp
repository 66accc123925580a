// The shape's surface noise with a sensor's depth error (ShapeConfig::depth_error): the error at
// the object's median depth, the floor it puts under the measured scatter, and nothing more.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "objects.hpp"
#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/grasp/reach.hpp"
#include "uwgrasp/grasp/shape.hpp"

namespace uwgrasp::grasp {
namespace {
using V3 = Eigen::Vector3f;

// Points at depths 0.5, 0.51, ..., 1.1 m (median 0.8 m), off the optical axis.
TEST(SensorNoise, IsTheDepthErrorAtTheObjectsMedianDepth) {
  std::vector<V3> pts;
  for (int i = 0; i <= 60; ++i)
    pts.emplace_back(0.2f - 0.01f * float(i % 7), 0.1f, 0.5f + 0.01f * float(i));
  EXPECT_NEAR(sensor_noise(pts, 0.003f), 0.003f * 0.8f * 0.8f, 1e-7f);
  EXPECT_FLOAT_EQ(sensor_noise(pts, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(sensor_noise({}, 0.003f), 0.0f);
  // Twice as far, four times the error (eq. 3.25 differentiated: dZ = Z^2 dd / (f B)).
  for (V3& p : pts) p *= 2.0f;
  EXPECT_NEAR(sensor_noise(pts, 0.003f), 4.0f * 0.003f * 0.8f * 0.8f, 1e-6f);
  // A large object: its median from a sample of its points, within a millimetre of depth.
  std::vector<V3> many;
  for (int i = 0; i < 100000; ++i)
    many.emplace_back(0.0f, 0.0f, 0.7f + 0.2f * float(i) / 100000.0f);
  EXPECT_NEAR(sensor_noise(many, 1.0f), 0.8f * 0.8f, 2.0f * 0.8f * 0.001f);
}

struct Seen {
  fixtures::ObjectCloud obj;
  Frames frames;
  std::vector<V3> level, normals;
  FloorPlane floor_c;
};

Seen barbell() {
  Seen s{
      fixtures::render_object(fixtures::Object::barbell, fixtures::View{}, 20000), {}, {}, {}, {}};
  FrameConfig fc;
  fc.camera.rpy.y() = s.obj.camera_pitch;
  s.frames = make_frames(fc);
  const Eigen::Vector3d n = s.obj.camera_from_world.linear().col(2);
  s.floor_c = FloorPlane(float(n.x()), float(n.y()), float(n.z()),
                         float(-n.dot(s.obj.camera_from_world.translation())));
  s.level = points_to_level(s.obj.cloud.points, s.frames);
  s.normals = directions_to_level(s.obj.cloud.normals, s.frames);
  return s;
}

ObjectShape shape_of(const Seen& s, const ShapeConfig& cfg) {
  const Surroundings scene{s.obj.cloud.points, true, s.floor_c};
  const SceneSight sight{s.obj.cloud.points, s.floor_c};
  return complete_shape(s.level, s.obj.cloud.points, s.frames, level_plane(scene, s.frames), cfg,
                        s.normals, &sight);
}

// Under the measured scatter the sensor's error changes nothing; over it, it is the noise the
// shape works with (its tolerances: the shadow test's, the symmetry search's), and the measured
// scatter stays what it was.
TEST(SensorNoise, FloorsTheMeasuredNoiseAndOnlyLiftsIt) {
  const Seen s = barbell();
  const ObjectShape plain = shape_of(s, ShapeConfig{});
  ASSERT_GT(plain.measured_noise, 0.0f);
  EXPECT_FLOAT_EQ(plain.noise, plain.measured_noise);
  EXPECT_FLOAT_EQ(plain.sensor_noise, 0.0f);
  // The median depth of the barbell's points, as sensor_noise takes it.
  const float depth = std::sqrt(sensor_noise(s.obj.cloud.points, 1.0f));
  ASSERT_GT(depth, 0.3f);
  // A sensor whose error at the object's depth is `times` the measured scatter.
  const auto with_error = [&](float times) {
    ShapeConfig cfg;
    cfg.depth_error = times * plain.measured_noise / (depth * depth);
    return shape_of(s, cfg);
  };
  const ObjectShape same = with_error(0.5f);
  EXPECT_FLOAT_EQ(same.noise, plain.noise);
  EXPECT_NEAR(same.sensor_noise, 0.5f * plain.measured_noise, 1e-6f);
  EXPECT_EQ(same.cells, plain.cells);
  EXPECT_EQ(same.mirrored_points, plain.mirrored_points);

  const ObjectShape floored = with_error(4.0f);
  EXPECT_FLOAT_EQ(floored.measured_noise, plain.measured_noise);
  EXPECT_NEAR(floored.noise, 4.0f * plain.measured_noise, 1e-6f);
  EXPECT_FLOAT_EQ(floored.noise, floored.sensor_noise);
}

}  // namespace
}  // namespace uwgrasp::grasp
