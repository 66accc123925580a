#include <gtest/gtest.h>
#include <pcl/ModelCoefficients.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>
#include <tbb/global_control.h>

#include "pcl_convert.hpp"
#include "shapes.hpp"
#include "uwgrasp/cloud/filters.hpp"
#include "uwgrasp/cloud/ransac.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace uwgrasp::cloud {

namespace {
Eigen::Vector4f pcl_plane(const Cloud& c, float dist) {
  pcl::SACSegmentation<pcl::PointXYZ> seg;
  seg.setOptimizeCoefficients(true);
  seg.setModelType(pcl::SACMODEL_PLANE);
  seg.setMethodType(pcl::SAC_RANSAC);
  seg.setDistanceThreshold(dist);
  seg.setMaxIterations(1000);
  seg.setInputCloud(test::to_pcl_xyz(c));
  pcl::PointIndices inl;
  pcl::ModelCoefficients m;
  seg.segment(inl, m);
  return {m.values[0], m.values[1], m.values[2], m.values[3]};
}

// Angle between plane normals (sign-free) and the offset difference after aligning signs.
void expect_same_plane(Eigen::Vector4f a, Eigen::Vector4f b, double deg, double metres) {
  if (a.head<3>().dot(b.head<3>()) < 0) b = -b;
  EXPECT_LT(test::angle_deg(a.head<3>(), b.head<3>()), deg);
  EXPECT_LT(std::abs(a[3] - b[3]), metres);
}
}  // namespace

TEST(Ransac, IterationCountIsEquation43) {
  // Thesis 8.2: 395245 of 398080 points on the plane, p = 99 %, n = 3 -> k = 1.19 -> 2.
  EXPECT_EQ(ransac_iterations(0.99, 395245.0 / 398080.0), 2.0);
  EXPECT_NEAR(std::log(0.01) / std::log(1 - std::pow(0.5, 3)), 34.49, 0.01);
  EXPECT_EQ(ransac_iterations(0.99, 0.5), 35.0);
  EXPECT_EQ(ransac_iterations(0.99, 1.0), 1.0);
  EXPECT_TRUE(std::isinf(ransac_iterations(0.99, 0.0)));
}

TEST(Ransac, FindsAKnownPlaneAmongOutliers) {
  // Plane 0.6x - 0.8z = -1.6 i.e. n = (0.6, 0, -0.8), d = 1.6, viewpoint at the origin.
  Cloud c;
  Rng r(5);
  const Eigen::Vector3f n(0.6f, 0.f, -0.8f);
  for (int i = 0; i < 4000; ++i) {
    const float u = float(r.uniform() * 2 - 1), v = float(r.uniform() * 2 - 1);
    const Eigen::Vector3f p = Eigen::Vector3f(0.8f * u, v, 0.6f * u) + 2.0f * n + 0.002f * float(r.normal()) * n;
    c.points.push_back(p);
  }
  for (int i = 0; i < 2000; ++i) c.points.emplace_back(r.uniform() * 4 - 2, r.uniform() * 4 - 2, r.uniform() * 4 - 2);
  make_unorganised(c);
  PlaneConfig cfg;
  cfg.max_iterations = 200;
  const PlaneResult p = fit_plane(c, cfg, 1);
  ASSERT_TRUE(p.found);
  // Oriented towards the viewpoint: n.v + d > 0 with v = 0 means d > 0.
  EXPECT_GT(p.coefficients[3], 0);
  expect_same_plane(p.coefficients, {-0.6f, 0.f, 0.8f, 2.0f}, 0.5, 0.002);
  EXPECT_GE(p.inliers.size(), 3990u);
  EXPECT_LE(p.iterations, 200u);
}

TEST(Ransac, SamePlaneAsPclSacSegmentation) {
  UWGRASP_DATA_OR_SKIP(sac, "clouds/sac_plane_test.pcd");
  UWGRASP_DATA_OR_SKIP(mug, "clouds/table_scene_mug_stereo_textured.pcd");
  for (const auto& path : {sac, mug}) {
    const Cloud c = remove_invalid(io::load_cloud(path)).cloud;
    PlaneConfig cfg;
    cfg.max_iterations = 1000;
    const PlaneResult ours = fit_plane(c, cfg, 1);
    ASSERT_TRUE(ours.found) << path;
    expect_same_plane(ours.coefficients, pcl_plane(c, cfg.distance), 0.5, 0.001);
  }
}

TEST(Ransac, SameResultForAnyThreadCount) {
  const Cloud c = test::plane_grid(300, 2.0f, 1.0f, 3, 0.003f);
  PlaneResult a, b;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    a = fit_plane(c, {}, 42);
  }
  {
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    b = fit_plane(c, {}, 42);
  }
  EXPECT_EQ(a.coefficients, b.coefficients);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.iterations, b.iterations);
}

TEST(Ransac, DegenerateInputsFindNoPlane) {
  EXPECT_FALSE(fit_plane(Cloud{}, {}, 1).found);
  Cloud two;
  two.points = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_FALSE(fit_plane(two, {}, 1).found);
  Cloud line;
  for (int i = 0; i < 100; ++i) line.points.emplace_back(0.01f * i, 0.02f * i, 1.f);
  make_unorganised(line);
  EXPECT_FALSE(fit_plane(line, {}, 1).found);
  // A sphere has no plane holding 5 % of its points within 1 mm.
  const Cloud ball = test::sphere(5000, 0.5f, {0, 0, 3});
  PlaneConfig cfg;
  cfg.distance = 0.001f;
  EXPECT_FALSE(fit_plane(ball, cfg, 1).found);
}

}  // namespace uwgrasp::cloud
