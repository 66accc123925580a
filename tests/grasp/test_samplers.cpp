#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <numbers>
#include <utility>

#include "objects.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/grasp/feasibility.hpp"
#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/grasp/samplers.hpp"
#include "shapes.hpp"

namespace uwgrasp::grasp {

namespace {
const Eigen::Matrix3d kI = Eigen::Matrix3d::Identity();

bool same(const std::vector<Candidate>& a, const std::vector<Candidate>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].position != b[i].position || a[i].rotation != b[i].rotation || a[i].source != b[i].source)
      return false;
  return true;
}
}  // namespace

TEST(Samplers, SeededAndIndependentOfThreadCount) {
  const Cloud c = test::sphere(2000, 0.1f, Eigen::Vector3f(0, 0, 1));
  SamplerConfig cfg;
  std::vector<Candidate> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = sample_uniform(c.points, cfg, kI, 5, 1000);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = sample_uniform(c.points, cfg, kI, 5, 1000);
  }
  EXPECT_TRUE(same(one, two));
  EXPECT_FALSE(same(one, sample_uniform(c.points, cfg, kI, 6, 1000)));
  EXPECT_TRUE(same(sample_normal(c.points, cfg, kI, 5, 300), sample_normal(c.points, cfg, kI, 5, 300)));
  // A continued run (first = 600) draws the same candidates as the tail of a longer one.
  const auto all = sample_normal(c.points, cfg, kI, 5, 1000);
  const auto tail = sample_normal(c.points, cfg, kI, 5, 400, 600);
  EXPECT_TRUE(same(std::vector<Candidate>(all.begin() + 600, all.end()), tail));
}

// Algorithm 1: k points, n variations each, offsets ~ N(0, sigma_p), rpy ~ N(0, sigma_theta).
TEST(Samplers, UniformWithLocalVariationStatistics) {
  const Cloud c = test::plane_grid(60, 0.5f, 0.0f);
  SamplerConfig cfg;
  cfg.variations = 10;
  cfg.sigma_p = Eigen::Vector3d(0.01, 0.02, 0.005);
  cfg.sigma_theta = Eigen::Vector3d(0.1, 0.2, 0.3);
  const auto s = sample_uniform(c.points, cfg, kI, 11, 20000);
  ASSERT_EQ(s.size(), 20000u);
  Eigen::Vector3d sp = Eigen::Vector3d::Zero(), st = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_EQ(s[i].source, s[i - i % 10].source);  // n variations of one drawn point
    const Eigen::Vector3d d = (s[i].position - c.points[s[i].source]).cast<double>();
    sp += d.cwiseProduct(d);
    const Eigen::Vector3d rpy = rpy_from_matrix(s[i].rotation.cast<double>());
    st += rpy.cwiseProduct(rpy);
  }
  sp = (sp / double(s.size())).cwiseSqrt();
  st = (st / double(s.size())).cwiseSqrt();
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(sp[a] / cfg.sigma_p[a], 1.0, 0.05) << a;
    EXPECT_NEAR(st[a] / cfg.sigma_theta[a], 1.0, 0.05) << a;
  }
}

// Algorithm 2: positions ~ N(centroid, alpha_p o sqrt(diag C)).
TEST(Samplers, NormalAroundTheCentroidStatistics) {
  Cloud c;
  Rng rng(3);
  for (int i = 0; i < 5000; ++i)
    c.points.emplace_back(float(1 + 0.2 * rng.uniform()), float(0.05 * rng.uniform()), 2.0f);
  SamplerConfig cfg;
  cfg.alpha_p = Eigen::Vector3d(2.0, 1.0, 1.0);
  const auto stats = [](const auto& pts, const auto& get) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero(), var = Eigen::Vector3d::Zero();
    for (const auto& p : pts) mean += get(p);
    mean /= double(pts.size());
    for (const auto& p : pts) var += (get(p) - mean).array().square().matrix();
    return std::pair(mean, Eigen::Vector3d((var / double(pts.size())).cwiseSqrt()));
  };
  const auto [cm, csd] = stats(c.points, [](const Eigen::Vector3f& p) { return Eigen::Vector3d(p.cast<double>()); });
  const auto s = sample_normal(c.points, cfg, kI, 4, 40000);
  const auto [mean, sd] = stats(s, [](const Candidate& k) { return Eigen::Vector3d(k.position.cast<double>()); });
  for (int a = 0; a < 3; ++a) {
    const double expected_sd = cfg.alpha_p[a] * csd[a];
    EXPECT_NEAR(mean[a], cm[a], 4 * expected_sd / std::sqrt(40000.0) + 1e-6) << a;  // 4 SE
    EXPECT_NEAR(sd[a], expected_sd, 0.02 * expected_sd + 1e-6) << a;
  }
}

// The gripper follows the vehicle attitude through its mount: R_LG = R(rpy) * R_BG.
TEST(Samplers, OrientationIsTheVehicleAttitudeThroughTheMount) {
  const Cloud c = test::plane_grid(10, 0.1f, 0.0f);
  SamplerConfig cfg;
  const Eigen::Matrix3d R_BG = quat_from_rpy(0, 0.5, 0).toRotationMatrix();
  const auto s = sample_normal(c.points, cfg, R_BG, 9, 50);
  const auto plain = sample_normal(c.points, cfg, kI, 9, 50);
  for (std::size_t i = 0; i < s.size(); ++i)
    EXPECT_TRUE(s[i].rotation.isApprox((plain[i].rotation.cast<double>() * R_BG).cast<float>(), 1e-5f));
}

TEST(Samplers, SurfaceApproachesAgainstTheNormal) {
  Cloud c = test::plane_grid(20, 0.2f, 0.0f);
  c.normals.assign(c.size(), Eigen::Vector3f(0, 0, 1));
  SamplerConfig cfg;
  const auto s = sample_surface(c.points, c.normals, cfg, 2, 200);
  for (const auto& k : s) {
    EXPECT_NEAR(k.rotation.col(0).z(), -1.0f, 1e-5f);
    EXPECT_NEAR(k.rotation.determinant(), 1.0f, 1e-5f);
  }
  EXPECT_THROW(sample_surface(c.points, {}, cfg, 2, 10), Error);
}

// Thesis 8.3: on the ring the centroid is in the hole - the normal sampler's candidates near
// it are infeasible, while uniform sampling follows the ring and finds feasible grasps.
TEST(Samplers, RingDefeatsTheNormalSamplerNotTheUniformOne) {
  const auto ring = fixtures::render_object(fixtures::Object::ring, {}, 30000);
  FrameConfig fc;
  fc.camera.rpy.y() = ring.camera_pitch;
  const Frames f = make_frames(fc);
  const std::vector<Eigen::Vector3f> pts = points_to_level(ring.cloud.points, f);
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  for (const auto& p : pts) centroid += p;
  centroid /= float(pts.size());
  const Gripper g = make_gripper({});
  const PointBvh bvh = build_bvh(pts);
  SamplerConfig cfg;
  const auto normal = sample_normal(pts, cfg, kI, 1, 3000);
  const auto nc = check_candidates(bvh, g, normal);
  std::size_t near = 0;
  for (std::size_t i = 0; i < normal.size(); ++i)
    if ((normal[i].position - centroid).norm() < 0.03f) {
      ++near;
      EXPECT_FALSE(nc[i].feasible());
    }
  EXPECT_GT(near, 20u);
  const auto uc = check_candidates(bvh, g, sample_uniform(pts, cfg, kI, 1, 3000));
  EXPECT_GT(count_rejections(uc)[0], 2 * count_rejections(nc)[0]);
}

TEST(Samplers, BadConfigIsNamed) {
  SamplerConfig cfg;
  cfg.sigma_p.x() = -1;
  EXPECT_THROW(check_sampler(cfg), Error);
  cfg = {};
  cfg.variations = 0;
  EXPECT_THROW(check_sampler(cfg), Error);
  EXPECT_THROW(sample_normal({}, SamplerConfig{}, kI, 1, 10), Error);
}

}  // namespace uwgrasp::grasp
