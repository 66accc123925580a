// Suspended particles (debris.hpp): small detached blobs off the seafloor are debris; surfaces,
// things resting on the floor and blobs a gap joins into something large are not. The grid's
// rule is checked against brute force: points nearer than the gap always share a verdict.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/debris.hpp"
#include "uwgrasp/grasp/reach.hpp"

namespace uwgrasp::grasp {
namespace {

using V3 = Eigen::Vector3f;

// A sphere's surface, densely sampled (a particle as a depth camera sees it: a blob).
void blob(std::vector<V3>& out, const V3& centre, float radius, int n, std::mt19937& rng) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (int i = 0; i < n; ++i) out.push_back(centre + radius * V3(g(rng), g(rng), g(rng)).normalized());
}

// A square patch in the plane z = height, side `side`, 2 mm apart.
void patch(std::vector<V3>& out, float x, float y, float height, float side) {
  for (float u = 0.0f; u <= side; u += 0.002f)
    for (float v = 0.0f; v <= side; v += 0.002f) out.push_back(V3(x + u, y + v, height));
}

const std::optional<Eigen::Vector4f> kFloor = Eigen::Vector4f(0, 0, 1, 0);  // z = 0

TEST(Debris, ParticlesOffTheFloorAreDebrisSurfacesAreNot) {
  std::mt19937 rng(3);
  std::vector<V3> p;
  blob(p, V3(0.0f, 0.0f, 0.5f), 0.003f, 120, rng);   // 0: marine snow, 6 mm, half a metre up
  const std::size_t a = p.size();
  patch(p, 0.2f, 0.0f, 0.3f, 0.06f);                  // a: a 6 cm plate, floating
  const std::size_t b = p.size();
  blob(p, V3(-0.2f, 0.0f, 0.004f), 0.003f, 120, rng);  // b: a pebble on the floor
  const std::size_t c = p.size();
  for (int k = 0; k < 4; ++k) blob(p, V3(0.0f, 0.3f + 0.008f * float(k), 0.4f), 0.003f, 60, rng);  // c: a chain, 3 cm
  const std::vector<char> d = debris(p, kFloor, 0.01f, 0.02f);
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(d[i], i < a) << "point " << i;
  (void)b, (void)c;
  // Off: nothing is debris; without a floor the pebble is a particle too.
  EXPECT_EQ(std::count(d.begin(), d.end(), 1), std::ptrdiff_t(a));
  const std::vector<char> off = debris(p, kFloor, 0.01f, 0.0f);
  EXPECT_EQ(std::count(off.begin(), off.end(), 1), 0);
  const std::vector<char> no_floor = debris(p, std::nullopt, 0.01f, 0.02f);
  for (std::size_t i = b; i < c; ++i) EXPECT_EQ(no_floor[i], 1);
}

TEST(Debris, PointsNearerThanTheGapShareTheirVerdict) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.3f, 0.3f), h(0.0f, 0.4f);
  std::vector<V3> p;
  for (int k = 0; k < 60; ++k) blob(p, V3(u(rng), u(rng), h(rng)), 0.001f + 0.01f * h(rng), 25, rng);
  const float gap = 0.01f;
  const std::vector<char> d = debris(p, kFloor, gap, 0.02f);
  std::size_t pairs = 0, flagged = std::size_t(std::count(d.begin(), d.end(), 1));
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j)
      if ((p[i] - p[j]).norm() < gap) {
        ++pairs;
        EXPECT_EQ(d[i], d[j]) << i << " " << j;
      }
  EXPECT_GT(pairs, 1000u);
  EXPECT_GT(flagged, 0u);  // the random blobs hold both kinds
  EXPECT_LT(flagged, p.size());
}

// The documented rule by brute force, pair by pair: points whose gap-grid cells are the same or
// adjacent (on every axis within one) join; a cluster is debris when its box's diagonal is at
// most `size` and no point lies within `gap` of the floor. Over a thousand cells, on both sides of
// every axis, so that the cell numbering grows many times over.
TEST(Debris, EqualsTheRuleByBruteForce) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> u(-0.4f, 0.4f), h(-0.05f, 0.4f), radius(0.002f, 0.02f);
  std::vector<V3> p;
  for (int k = 0; k < 150; ++k) blob(p, V3(u(rng), u(rng), h(rng)), radius(rng), 16, rng);
  const float gap = 0.01f, size = 0.03f;
  std::vector<Eigen::Vector3i> cell;
  for (const V3& q : p) cell.push_back((q / gap).array().floor().cast<int>());
  std::vector<std::size_t> root(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) root[i] = i;
  const auto find = [&](std::size_t a) {
    while (root[a] != a) a = root[a];
    return a;
  };
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j)
      if ((cell[i] - cell[j]).cwiseAbs().maxCoeff() <= 1) root[find(j)] = find(i);
  std::vector<V3> lo(p.size(), V3::Constant(1e9f)), hi(p.size(), V3::Constant(-1e9f));
  std::vector<char> rests(p.size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t r = find(i);
    lo[r] = lo[r].cwiseMin(p[i]), hi[r] = hi[r].cwiseMax(p[i]);
    if (std::abs(p[i].z()) <= gap) rests[r] = 1;
  }
  std::vector<Eigen::Vector3i> distinct = cell;
  const auto before = [](const Eigen::Vector3i& x, const Eigen::Vector3i& y) {
    return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
  };
  std::sort(distinct.begin(), distinct.end(), before);
  EXPECT_GT(std::unique(distinct.begin(), distinct.end()) - distinct.begin(),
            1000);  // many growths
  const std::vector<char> d = debris(p, kFloor, gap, size);
  std::size_t flagged = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t r = find(i);
    const char expected = !rests[r] && (hi[r] - lo[r]).norm() <= size;
    ASSERT_EQ(d[i], expected) << "point " << i;
    flagged += std::size_t(expected);
  }
  EXPECT_GT(flagged, p.size() / 10);  // both kinds, many of each
  EXPECT_LT(flagged, p.size() - p.size() / 10);
}

TEST(Debris, TheVehicleIsNotBlockedByAParticle) {
  // The gripper at the origin of L facing +x, the hull behind it; a particle where the hull sits.
  FrameConfig fc;
  fc.gripper.position = Eigen::Vector3d(0.35, 0.0, 0.12);
  const Frames f = make_frames(fc);
  const Gripper g = make_gripper(GripperConfig{});
  ReachConfig cfg;
  const std::vector<Solid> solids = vehicle_solids(g, f, cfg);
  std::mt19937 rng(5);
  std::vector<V3> level;
  blob(level, V3(-0.35f, 0.0f, -0.12f), 0.003f, 150, rng);
  std::vector<V3> camera;  // the same points in the camera frame, as Surroundings holds them
  for (const V3& q : level) camera.push_back((f.level_from_camera.inverse() * q.cast<double>()).cast<float>());
  Surroundings s;
  s.points = camera;
  Candidate c;
  c.position = V3::Zero();
  c.rotation = Eigen::Matrix3f::Identity();
  EXPECT_EQ(reach_check(make_obstacles(s, f, cfg), solids, c, cfg), Reject::none);
  cfg.debris_size = 0.0;
  EXPECT_EQ(reach_check(make_obstacles(s, f, cfg), solids, c, cfg), Reject::hull_collision);
}

TEST(Debris, BadSettingsAreRefused) {
  const Gripper g = make_gripper(GripperConfig{});
  FrameConfig fc;
  fc.gripper.position = Eigen::Vector3d(0.35, 0.0, 0.12);
  ReachConfig cfg;
  cfg.debris_gap = 0.0;
  EXPECT_THROW(vehicle_solids(g, make_frames(fc), cfg), Error);
  cfg.debris_gap = 0.01, cfg.debris_size = -1.0;
  EXPECT_THROW(vehicle_solids(g, make_frames(fc), cfg), Error);
}

}  // namespace
}  // namespace uwgrasp::grasp
