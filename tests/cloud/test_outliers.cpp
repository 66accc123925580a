#include <gtest/gtest.h>
#include <pcl/filters/statistical_outlier_removal.h>

#include "pcl_convert.hpp"
#include "shapes.hpp"
#include "uwgrasp/cloud/filters.hpp"
#include "uwgrasp/cloud/outliers.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace uwgrasp::cloud {

namespace {
std::vector<std::uint32_t> pcl_sor(const Cloud& c, int k, double mul) {
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
  sor.setInputCloud(test::to_pcl_xyz(c));
  sor.setMeanK(k);
  sor.setStddevMulThresh(mul);
  pcl::Indices kept;
  sor.filter(kept);
  return {kept.begin(), kept.end()};
}
}  // namespace

TEST(Outliers, SameKeptPointsAsPclOnARealScan) {
  UWGRASP_DATA_OR_SKIP(path, "clouds/milk_color.pcd");
  const Cloud c = remove_invalid(io::load_cloud(path)).cloud;
  for (std::uint32_t k : {8u, 20u}) {
    const Filtered ours = remove_outliers(c, {true, k, 1.0});
    const auto ref = pcl_sor(c, int(k), 1.0);
    EXPECT_EQ(ours.indices, ref) << "k = " << k;
    EXPECT_LT(ours.indices.size(), c.size());  // the thesis's mu + sigma removes something
    // From longer lists found beforehand (as preprocess shares them with the normals).
    const KdTree tree(c.points);
    EXPECT_EQ(remove_outliers(c, {true, k, 1.0}, knn_all(tree, c.points, 30)).indices, ref);
    EXPECT_THROW(remove_outliers(c, {true, k, 1.0}, knn_all(tree, c.points, k)), Error);
  }
}

TEST(Outliers, RemovesPlantedOutliersAndKeepsTheSurface) {
  Cloud c = test::plane_grid(60, 1.0f, 2.0f, 1);
  const std::size_t surface = c.size();
  Rng r(7);
  for (int i = 0; i < 20; ++i)
    c.points.emplace_back(r.uniform() * 4 - 2, r.uniform() * 4 - 2, 3 + r.uniform());
  make_unorganised(c);
  const Filtered f = remove_outliers(c, {true, 10, 1.0});
  for (auto i : f.indices) EXPECT_LT(i, surface) << "outlier " << i << " kept";
  EXPECT_GT(f.indices.size(), surface * 8 / 10);
}

TEST(Outliers, TinyCloudsPassUnchanged) {
  Cloud c;
  c.points = {{0, 0, 0}, {1, 0, 0}, {0, 5, 0}};
  make_unorganised(c);
  EXPECT_EQ(remove_outliers(c, {true, 10, 1.0}).indices.size(), 3u);
  EXPECT_TRUE(remove_outliers(Cloud{}, {true, 10, 1.0}).cloud.empty());
}

}  // namespace uwgrasp::cloud
