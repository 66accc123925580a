#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "uwgrasp/core/error.hpp"
#include "objects.hpp"
#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/grasp/occlusion.hpp"

namespace uwgrasp::grasp {

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();

// A square plate facing the camera at depth z: a grid of points with `step` spacing.
std::vector<Eigen::Vector3f> plate(float z, float half, float step) {
  std::vector<Eigen::Vector3f> out;
  for (float x = -half; x <= half + 1e-6f; x += step)
    for (float y = -half; y <= half + 1e-6f; y += step) out.emplace_back(x, y, z);
  return out;
}

// A gripper 2.4 cm across, so that where its parts sit is easy to state.
Gripper small_gripper() {
  GripperConfig c;
  c.max_aperture = 0.02f, c.finger_length = 0.01f, c.finger_width = 0.002f;
  c.finger_height = 0.005f, c.palm_depth = 0.002f, c.palm_height = 0.006f;
  c.body_length = 0.004f, c.body_width = 0.006f, c.body_height = 0.006f, c.clearance = 0.001f;
  return make_gripper(c);
}

Candidate at(float x, float y, float z) {
  Candidate c;
  c.position = Eigen::Vector3f(x, y, z);
  return c;
}
}  // namespace

// Every bin holds the nearest depth of the points whose bin is within one of it, by brute force.
TEST(Occlusion, DepthMapIsTheDilatedNearestDepth) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> xy(-0.2f, 0.2f), depth(0.4f, 0.9f);
  std::vector<Eigen::Vector3f> pts(3000);
  for (auto& p : pts) p = Eigen::Vector3f(xy(rng), xy(rng), depth(rng));
  pts.emplace_back(0.1f, 0.1f, -0.5f);  // behind the camera: ignored
  const float res = 0.01f, inverse = 1.0f / res;
  const DepthMap m = make_depth_map(pts, res);
  ASSERT_FALSE(m.depth.empty());
  const auto bin = [&](float v) { return static_cast<int>(std::floor(v * inverse)); };
  for (int v = m.v0 - 2; v < m.v0 + m.height + 2; ++v)
    for (int u = m.u0 - 2; u < m.u0 + m.width + 2; ++u) {
      float want = kInf;
      for (const auto& p : pts) {
        if (!(p.z() > 0.0f)) continue;
        const float iz = 1.0f / p.z();
        if (std::abs(bin(p.x() * iz) - u) <= 1 && std::abs(bin(p.y() * iz) - v) <= 1) want = std::min(want, p.z());
      }
      ASSERT_EQ(m.at_bin(u, v), want) << u << " " << v;
    }
  // at() is at_bin() of the point's bin.
  EXPECT_EQ(m.at(0.05f, -0.02f), m.at_bin(bin(0.05f), bin(-0.02f)));
}

// range() bounds the seen depths over any rectangle of bins (it may read a few more around it)
// and is exact for the whole map; brute force over the bins as the oracle.
TEST(Occlusion, DepthRangeBoundsTheBinsItCovers) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> xy(-0.2f, 0.2f), depth(0.4f, 0.9f);
  std::vector<Eigen::Vector3f> pts(400);
  for (auto& p : pts) p = Eigen::Vector3f(xy(rng), xy(rng) * 0.5f, depth(rng));
  const DepthMap m = make_depth_map(pts, 0.01f);
  ASSERT_GT(m.width, 8);
  std::uniform_int_distribution<int> u(m.u0 - 3, m.u0 + m.width + 3), v(m.v0 - 3, m.v0 + m.height + 3);
  int narrow = 0;
  for (int q = 0; q < 2000; ++q) {
    // minmax of an initializer list returns values; of two temporaries it would return
    // references to them.
    const auto [ua, ub] = std::minmax({u(rng), u(rng)});
    const auto [va, vb] = std::minmax({v(rng), v(rng)});
    float lo = kInf, hi = -kInf;
    for (int y = va; y <= vb; ++y)
      for (int x = ua; x <= ub; ++x)
        if (const float d = m.at_bin(x, y); d != kInf) lo = std::min(lo, d), hi = std::max(hi, d);
    const auto [rlo, rhi] = m.range(ua, ub, va, vb);
    ASSERT_LE(rlo, lo) << ua << " " << ub << " " << va << " " << vb;
    ASSERT_GE(rhi, hi) << ua << " " << ub << " " << va << " " << vb;
    narrow += rlo > depth.a() || rhi < depth.b();  // informative: not the whole map's range
  }
  EXPECT_GT(narrow, 200);
  const auto [all_lo, all_hi] = m.range(m.u0, m.u0 + m.width - 1, m.v0, m.v0 + m.height - 1);
  EXPECT_EQ(all_lo, *std::min_element(m.depth.begin(), m.depth.end()));
  float far = -kInf;
  for (const float d : m.depth) far = d == kInf ? far : std::max(far, d);
  EXPECT_EQ(all_hi, far);
  EXPECT_EQ(m.range(m.u0 - 9, m.u0 - 5, m.v0, m.v0 + 3), std::make_pair(kInf, -kInf));  // outside
}

// Clearing whole patches gives every sample's answer: on the barbell's view, 3000 candidates
// spread over all poses are occluded or not alike with and without it, both answers occurring.
TEST(Occlusion, PatchClearingMatchesTestingEverySample) {
  const auto obj = fixtures::render_object(fixtures::Object::barbell, {}, 20000);
  FrameConfig fc;
  fc.camera.rpy.y() = obj.camera_pitch;
  const Frames f = make_frames(fc);
  const auto level = points_to_level(obj.cloud.points, f);
  const OcclusionConfig cfg;
  const DepthMap m = make_depth_map(obj.cloud.points, cfg.resolution);
  const PartSamples samples = part_samples(make_gripper({}), cfg.spacing);
  const Pose camera_from_level = f.level_from_camera.inverse();
  const auto cand = sample_normal(level, SamplerConfig{}, f.body_from_gripper.linear(), 7, 3000);
  int hidden = 0;
  for (std::size_t i = 0; i < cand.size(); ++i) {
    const bool all = occluded(m, samples, cand[i], camera_from_level, cfg, false);
    ASSERT_EQ(occluded(m, samples, cand[i], camera_from_level, cfg), all) << i;
    hidden += all;
  }
  EXPECT_GT(hidden, 100);
  EXPECT_LT(hidden, 2900);
}

TEST(Occlusion, EmptyAndBadMaps) {
  const std::vector<Eigen::Vector3f> behind{Eigen::Vector3f(0, 0, -1)};
  const DepthMap m = make_depth_map(behind, 0.003f);
  EXPECT_TRUE(m.depth.empty());
  EXPECT_EQ(m.at(0, 0), kInf);
  const Gripper g = small_gripper();
  EXPECT_FALSE(occluded(m, part_samples(g, 0.002f), at(0, 0, 0.5f), Pose::Identity(), {}));
  EXPECT_THROW(make_depth_map(behind, 0.0f), Error);
  EXPECT_THROW(part_samples(g, -1.0f), Error);
}

// A plate at 0.5 m: parts hidden just behind it are occluded; in front of it, beyond the
// assumed thickness, beside it or behind the camera they are not.
TEST(Occlusion, PartsInThePlateShadow) {
  const std::vector<Eigen::Vector3f> pts = plate(0.5f, 0.1f, 0.002f);
  const OcclusionConfig cfg;  // 3 cm thick, 3 mm tolerance
  const DepthMap m = make_depth_map(pts, cfg.resolution);
  const Gripper g = small_gripper();  // parts within +-3 mm of the centre along z
  const auto samples = part_samples(g, 0.002f);
  ASSERT_FALSE(samples.patches.empty());
  const Pose I = Pose::Identity();
  EXPECT_TRUE(occluded(m, samples, at(0, 0, 0.512f), I, cfg));    // 9-15 mm behind
  EXPECT_TRUE(occluded(m, samples, at(0.05f, -0.05f, 0.52f), I, cfg));
  EXPECT_FALSE(occluded(m, samples, at(0, 0, 0.45f), I, cfg));    // in front
  EXPECT_FALSE(occluded(m, samples, at(0, 0, 0.56f), I, cfg));    // 5.7-6.3 cm behind
  EXPECT_FALSE(occluded(m, samples, at(0.5f, 0, 0.512f), I, cfg));  // beside the plate
  EXPECT_FALSE(occluded(m, samples, at(0, 0, -0.5f), I, cfg));    // behind the camera
  // Touching the surface from behind by less than the tolerance is allowed: parts end 1 mm
  // behind the plate.
  EXPECT_FALSE(occluded(m, samples, at(0, 0, 0.498f), I, cfg));
  // The same through a camera pose: the level frame 1 m along camera -z.
  Pose camera_from_level = Pose::Identity();
  camera_from_level.translation() = Eigen::Vector3d(0, 0, 1.0);
  EXPECT_TRUE(occluded(m, samples, at(0, 0, -0.488f), camera_from_level, cfg));
  EXPECT_FALSE(occluded(m, samples, at(0, 0, -0.55f), camera_from_level, cfg));
}

}  // namespace uwgrasp::grasp
