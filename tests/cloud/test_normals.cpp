#include <gtest/gtest.h>
#include <pcl/features/normal_3d.h>
#include <pcl/search/kdtree.h>

#include "pcl_convert.hpp"
#include "shapes.hpp"
#include "uwgrasp/cloud/filters.hpp"
#include "uwgrasp/cloud/normals.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace uwgrasp::cloud {

TEST(Normals, PlaneNormalsFaceTheViewpointWithZeroCurvature) {
  Cloud c = test::plane_grid(40, 1.0f, 2.0f);
  compute_normals(c, {});
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_LT(test::angle_deg(c.normals[i], {0, 0, -1}), 0.01) << i;  // towards the origin
    EXPECT_LT(c.curvature[i], 1e-6f);
  }
  c.viewpoint = {0, 0, 5};
  compute_normals(c, {});
  EXPECT_LT(test::angle_deg(c.normals[0], {0, 0, 1}), 0.01);
}

TEST(Normals, SphereNormalsAreRadialWithTheCapCurvature) {
  const int n = 20000, k = 20;
  Cloud c = test::sphere(n, 1.0f, {0, 0, 0});
  c.viewpoint = {0, 0, 0};  // inside: normals point inwards
  compute_normals(c, {std::uint32_t(k), 0});
  // Curvature of a uniform spherical cap holding k of n points: cos(a) = 1 - 2k/n,
  // var_normal = (1 - cos a)^2 / 12, var_tangent = (1 - E[u^2]) / 2 per axis.
  const double ca = 1.0 - 2.0 * k / n, eu2 = (1 - ca * ca * ca) / (3 * (1 - ca));
  const double vn = (1 - ca) * (1 - ca) / 12, vt = (1 - eu2) / 2;
  const double expected = vn / (vn + 2 * vt);
  double mean_curv = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_LT(test::angle_deg(c.normals[i], -c.points[i]), 1.0) << i;
    mean_curv += c.curvature[i];
  }
  EXPECT_NEAR(mean_curv / n, expected, 0.25 * expected);
}

TEST(Normals, WithinTwoDegreesOfPclOnRealClouds) {
  UWGRASP_DATA_OR_SKIP(milk, "clouds/milk_color.pcd");
  UWGRASP_DATA_OR_SKIP(mug, "clouds/table_scene_mug_stereo_textured.pcd");
  for (const auto& path : {milk, mug}) {
    Cloud c = remove_invalid(io::load_cloud(path)).cloud;
    c.viewpoint = Eigen::Vector3f::Zero();
    compute_normals(c, {20, 0});
    pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
    ne.setInputCloud(test::to_pcl_xyz(c));
    ne.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
    ne.setKSearch(20);
    ne.setViewPoint(0, 0, 0);
    pcl::PointCloud<pcl::Normal> ref;
    ne.compute(ref);
    std::size_t close = 0, curv_close = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      close += test::angle_deg(c.normals[i], ref[i].getNormalVector3fMap()) <= 2.0;
      curv_close += std::abs(c.curvature[i] - ref[i].curvature) <= 1e-3f;
    }
    EXPECT_GE(close, c.size() * 99 / 100) << path;
    EXPECT_GE(curv_close, c.size() * 99 / 100) << path;
  }
}

TEST(Normals, TooFewNeighboursGiveNan) {
  Cloud c;
  c.points = {{0, 0, 1}, {1, 0, 1}};
  make_unorganised(c);
  compute_normals(c, {});
  EXPECT_TRUE(std::isnan(c.normals[0].x()));
  EXPECT_TRUE(std::isnan(c.curvature[1]));
  Cloud line;
  for (int i = 0; i < 10; ++i) line.points.emplace_back(0.1f * i, 0.f, 1.f);
  make_unorganised(line);
  compute_normals(line, {5, 0});  // collinear: normal undefined but finite, never NaN
  for (const auto& nrm : line.normals) EXPECT_NEAR(nrm.norm(), 1.0f, 1e-5f);
  EXPECT_THROW(compute_normals(line, {2, 0}), Error);
  Cloud empty;
  compute_normals(empty, {});
  EXPECT_TRUE(empty.normals.empty());
}

}  // namespace uwgrasp::cloud
