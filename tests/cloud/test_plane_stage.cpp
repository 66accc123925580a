// The plane stage's refinements (plane_stage.hpp) against brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <unordered_set>

#include "uwgrasp/cloud/plane_stage.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::cloud {

namespace {
// supports_the_rest as first written: a hash set of the inliers' cells, each point sequentially.
bool supports_reference(const Cloud& cur, const PlaneConfig& cfg, const PlaneResult& plane) {
  const Eigen::Vector4f& n = plane.coefficients;
  const Eigen::Vector3f normal = n.head<3>();
  const Eigen::Vector3f a = normal.unitOrthogonal(), b = normal.cross(a);
  const float cell = std::max(2.0f * cfg.distance, 0.01f);
  const auto key = [&](const Eigen::Vector3f& p, int du, int dv) {
    const auto u = std::int64_t(std::floor(a.dot(p) / cell)) + du, v = std::int64_t(std::floor(b.dot(p) / cell)) + dv;
    return (u << 32) ^ (v & 0xffffffff);
  };
  std::unordered_set<std::int64_t> over;
  for (const auto i : plane.inliers) over.insert(key(cur.points[i], 0, 0));
  const float sensor = normal.dot(cur.viewpoint) + n[3];
  std::size_t front = 0, behind = 0;
  for (const auto& p : cur.points) {
    const float d = normal.dot(p) + n[3];
    if (std::abs(d) <= 3.0f * cfg.distance) continue;
    bool inside = false;
    for (int du = -1; du <= 1 && !inside; ++du)
      for (int dv = -1; dv <= 1 && !inside; ++dv) inside = over.count(key(p, du, dv)) > 0;
    if (inside) ++(d * sensor > 0.0f ? front : behind);
  }
  return front >= behind;
}

// A tilted plane 2 m from the camera: inlier patches (one, or two `apart` metres apart), and
// points off it in front of and behind it, over the patches and beyond them, in shares drawn
// near one half so that either answer comes up.
struct Scene {
  Cloud cloud;
  PlaneResult plane;
};
Scene random_scene(std::uint64_t seed, float apart) {
  Rng rng(seed);
  Scene s;
  const Eigen::Vector3f normal = Eigen::Vector3f(0.2f, -1.0f, -0.3f).normalized();
  const Eigen::Vector3f origin(0.0f, 1.0f, 2.0f);
  s.plane.found = true;
  s.plane.coefficients = Eigen::Vector4f(normal.x(), normal.y(), normal.z(), -normal.dot(origin));
  const Eigen::Vector3f a = normal.unitOrthogonal(), b = normal.cross(a);
  const double front_share = 0.4 + 0.2 * rng.uniform();
  for (int i = 0; i < 4000; ++i) {
    const float du = float(rng.uniform() - 0.5), dv = float(rng.uniform() - 0.5);
    const float shift = (i % 2 == 1 && apart > 0.0f) ? apart : 0.0f;
    const Eigen::Vector3f on = origin + (du + shift) * a + dv * b;
    s.plane.inliers.push_back(std::uint32_t(s.cloud.points.size()));
    s.cloud.points.push_back(on + float(0.002 * rng.normal()) * normal);
    const float h = float(0.02 + 0.2 * rng.uniform()) * (rng.uniform() < front_share ? 1.0f : -1.0f);
    const float beyond = rng.uniform() < 0.2 ? 2.0f : 0.0f;  // beyond the patch: not counted
    s.cloud.points.push_back(on + h * normal + beyond * b);
  }
  make_unorganised(s.cloud);
  return s;
}
}  // namespace

// The bitmap of the inliers' cells (a frame's floor) and the hash set (inliers spread over more
// than 2^24 cells) answer as the sequential hash set did.
TEST(PlaneStage, SupportsTheRestAsBruteForce) {
  PlaneConfig cfg;
  int yes = 0, no = 0;
  for (const float apart : {0.0f, 2000.0f})
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
      const Scene s = random_scene(seed, apart);
      const bool expected = supports_reference(s.cloud, cfg, s.plane);
      ASSERT_EQ(supports_the_rest(s.cloud, cfg, s.plane), expected) << "seed " << seed << " apart " << apart;
      ++(expected ? yes : no);
    }
  EXPECT_GT(yes, 10);  // both answers were tested
  EXPECT_GT(no, 10);
  PlaneResult none = random_scene(1, 0.0f).plane;
  const Cloud c = random_scene(1, 0.0f).cloud;
  none.inliers.clear();  // no cell over the plane: nothing counts, front 0 >= behind 0
  EXPECT_TRUE(supports_the_rest(c, cfg, none));
}

}  // namespace uwgrasp::cloud
