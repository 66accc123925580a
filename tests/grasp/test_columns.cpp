// The columns under the rest of the scene: a finger in a neighbour's hidden back cuts them, one
// in the free space the camera saw does not; a column is solid only where something seen hides
// it; the grid agrees with every column; the reach check takes only the rest of the scene's.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "grasp_helpers.hpp"
#include "uwgrasp/grasp/columns.hpp"
#include "uwgrasp/grasp/reach.hpp"

namespace uwgrasp::grasp {
namespace {

using test::candidate;
using V3 = Eigen::Vector3f;

// L: z down, the seafloor z = 0 (n = -z, the camera on its + side). The camera 0.6 m back and
// 0.45 m up, looking 35 degrees down (optical x = L's y, z forward).
const Eigen::Vector4f kFloor(0.0f, 0.0f, -1.0f, 0.0f);
Pose level_from_camera() {
  const double a = 35.0 * M_PI / 180.0;
  const Eigen::Vector3d z(std::cos(a), 0.0, std::sin(a)), x = Eigen::Vector3d::UnitY();
  Pose T = Pose::Identity();
  T.linear().col(0) = x, T.linear().col(1) = z.cross(x), T.linear().col(2) = z;
  T.translation() = Eigen::Vector3d(-0.6, 0.0, -0.45);
  return T;
}

std::vector<V3> to_camera(const std::vector<V3>& level) {
  const Pose C = level_from_camera().inverse();
  std::vector<V3> out;
  for (const V3& p : level) out.push_back((C * p.cast<double>()).cast<float>());
  return out;
}

// The points of an upright can (radius 3 cm, 11 cm tall, on the floor at (x, y)) the camera sees:
// its side and top sampled every 2 mm, kept where they face the camera.
std::vector<V3> seen_can(float x, float y) {
  const V3 cam = level_from_camera().translation().cast<float>();
  const float r = 0.03f, h = 0.11f;
  std::vector<V3> out;
  for (int k = 0; k < 94; ++k) {
    const float a = float(k) * 2.0f * float(M_PI) / 94.0f;
    const V3 n(std::cos(a), std::sin(a), 0.0f);
    for (float z = 0.0f; z <= h; z += 0.002f) {
      const V3 p(x + r * n.x(), y + r * n.y(), -z);
      if (n.dot(cam - p) > 0.0f) out.push_back(p);
    }
  }
  for (float u = -r; u <= r; u += 0.002f)
    for (float v = -r; v <= r; v += 0.002f)
      if (u * u + v * v <= r * r) out.push_back(V3(x + u, y + v, -h));
  return out;
}

// A finger-sized solid (5 x 1 x 1.5 cm) pointing down, closing along y.
Solid finger() {
  Solid s;
  s.half = V3(0.025f, 0.005f, 0.0075f);
  return s;
}
const V3 kDown = V3::UnitZ(), kAcross = V3::UnitY();

std::size_t above_floor(const std::vector<V3>& pts) {
  return std::size_t(std::count_if(pts.begin(), pts.end(), [](const V3& p) { return p.z() < 0.0f; }));
}
ReachConfig at_the_grasp() {  // no approach: the columns are checked at the grasp pose only
  ReachConfig cfg;
  cfg.standoff = 0.0, cfg.debris_size = 0.0;
  return cfg;
}

TEST(Columns, AFingerInANeighboursHiddenBackCutsItsColumnsNotInTheSpaceSeenBeforeIt) {
  const std::vector<V3> can = seen_can(0.0f, 0.075f);
  const Columns cols = make_columns(can, kFloor, to_camera(can), level_from_camera().inverse());
  ASSERT_EQ(cols.points.size(), above_floor(can));  // those on the floor stand for none
  // Behind the can's seen front, 4 cm up, overlapping the can by 2.5 mm: no seen point is in
  // it (the check of points alone passes it), the columns under the top are.
  const Candidate back = candidate(V3(0.012f, 0.045f, -0.04f), kDown, kAcross);
  Obstacles o;
  o.bvh = build_bvh(can);
  const Solid f = finger();
  EXPECT_EQ(reach_check(o, std::span(&f, 1), back, at_the_grasp()), Reject::none);
  EXPECT_TRUE(cuts_column(cols, f, back));
  // In front of the can, in the space the camera saw: free.
  EXPECT_FALSE(cuts_column(cols, f, candidate(V3(-0.045f, 0.075f, -0.03f), kDown, kAcross)));
  // Beside it, clear of its footprint: free.
  EXPECT_FALSE(cuts_column(cols, f, candidate(V3(0.012f, 0.025f, -0.04f), kDown, kAcross)));
}

TEST(Columns, AColumnIsSolidOnlyWhereSomethingSeenHidesIt) {
  const std::vector<V3> top = {V3(0.0f, 0.0f, -0.1f)};  // a point 10 cm above the floor
  const Solid f = finger();
  const Candidate under = candidate(V3(0.0f, 0.0f, -0.04f), kDown, kAcross);
  // Seen alone, the camera sees the floor under it: the column is free.
  EXPECT_FALSE(cuts_column(make_columns(top, kFloor, to_camera(top), level_from_camera().inverse()), f, under));
  // A wall seen in front of it hides the column: solid.
  std::vector<V3> seen = top;
  for (float y = -0.06f; y <= 0.06f; y += 0.002f)
    for (float z = -0.12f; z <= 0.0f; z += 0.002f) seen.push_back(V3(-0.1f, y, z));
  EXPECT_TRUE(cuts_column(make_columns(top, kFloor, to_camera(seen), level_from_camera().inverse()), f, under));
}

TEST(Columns, TheGridAgreesWithEveryColumn) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.3f, 0.3f), up(-0.25f, 0.02f);
  std::vector<V3> pts;
  for (int k = 0; k < 600; ++k) pts.push_back(V3(u(rng), u(rng), up(rng)));  // some below the floor
  std::vector<V3> seen = pts;  // and a screen in front that hides part of them
  for (float y = -0.3f; y <= 0.0f; y += 0.004f)
    for (float z = -0.3f; z <= 0.0f; z += 0.004f) seen.push_back(V3(-0.35f, y, z));
  const Columns cols = make_columns(pts, kFloor, to_camera(seen), level_from_camera().inverse(), 0.03f);
  EXPECT_LT(cols.points.size(), pts.size());  // the points below the floor stand for none
  const Solid f = finger();
  int cut = 0;
  for (int i = 0; i < 500; ++i) {
    const Candidate c = candidate(V3(u(rng), u(rng), 0.5f * up(rng)), V3(u(rng), u(rng), u(rng)),
                                  V3(u(rng), u(rng), u(rng)));
    const bool fast = cuts_column(cols, f, c);
    ASSERT_EQ(fast, cuts_column_brute(cols, f, c)) << "candidate " << i;
    cut += fast;
  }
  EXPECT_GT(cut, 25);
  EXPECT_LT(cut, 475);
}

TEST(Columns, TheReachCheckTakesTheColumnsOfTheRestOfTheSceneOnly) {
  const std::vector<V3> can = seen_can(0.0f, 0.075f);
  Frames frames;
  frames.level_from_camera = level_from_camera();
  const std::vector<V3> camera = to_camera(can);
  // The floor in the camera frame, the camera on its + side.
  const Eigen::Vector3d n = frames.level_from_camera.linear().transpose() * Eigen::Vector3d(0, 0, -1);
  const double d = -n.dot(frames.level_from_camera.inverse().translation());
  std::vector<char> rests(can.size(), 1);
  Surroundings s{camera, true, Eigen::Vector4f(float(n.x()), float(n.y()), float(n.z()), float(d)), rests};
  const ReachConfig cfg = at_the_grasp();
  const Solid f[] = {[] { Solid solid = finger(); solid.at_grasp = Reject::scene_collision; return solid; }()};
  const Candidate back = candidate(V3(0.012f, 0.045f, -0.04f), kDown, kAcross);
  const Obstacles o = make_obstacles(s, frames, cfg);
  EXPECT_EQ(o.columns.points.size(), above_floor(can));
  EXPECT_EQ(reach_check(o, f, back, cfg), Reject::scene_collision);
  EXPECT_EQ(reach_brute(points_to_level(camera, frames), o, f, back, cfg), Reject::scene_collision);
  // The same points as the object's own (its shape models its back): no columns.
  std::fill(rests.begin(), rests.end(), 0);
  EXPECT_EQ(reach_check(make_obstacles(s, frames, cfg), f, back, cfg), Reject::none);
}

}  // namespace
}  // namespace uwgrasp::grasp
