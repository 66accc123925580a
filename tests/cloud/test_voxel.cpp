#include <gtest/gtest.h>
#include <pcl/filters/voxel_grid.h>
#include <tbb/global_control.h>

#include "pcl_convert.hpp"
#include "shapes.hpp"
#include "uwgrasp/cloud/filters.hpp"
#include "uwgrasp/cloud/voxel.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace uwgrasp::cloud {

namespace {
pcl::PointCloud<pcl::PointXYZ> pcl_voxel(const Cloud& c, float leaf) {
  pcl::VoxelGrid<pcl::PointXYZ> vg;
  vg.setInputCloud(test::to_pcl_xyz(c));
  vg.setLeafSize(leaf, leaf, leaf);
  pcl::PointCloud<pcl::PointXYZ> out;
  vg.filter(out);
  return out;
}

void expect_same_as_pcl(const Cloud& c, float leaf) {
  const VoxelResult ours = voxel_grid(c, {true, leaf, 1});
  const auto ref = pcl_voxel(c, leaf);
  ASSERT_EQ(ours.cloud.size(), ref.size()) << "leaf " << leaf;
  // Both order voxels by index, so centroids compare point by point.
  for (std::size_t i = 0; i < ref.size(); ++i)
    ASSERT_LT((ours.cloud.points[i] - ref[i].getVector3fMap()).norm(), 1e-5f) << i;
}
}  // namespace

TEST(Voxel, SameVoxelsAndCentroidsAsPclOnRealClouds) {
  UWGRASP_DATA_OR_SKIP(mug, "clouds/table_scene_mug_stereo_textured.pcd");
  UWGRASP_DATA_OR_SKIP(milk, "clouds/milk_color.pcd");
  const Cloud a = remove_invalid(io::load_cloud(mug)).cloud;
  const Cloud b = remove_invalid(io::load_cloud(milk)).cloud;
  for (float leaf : {0.0025f, 0.01f, 0.03f}) {
    expect_same_as_pcl(a, leaf);
    expect_same_as_pcl(b, leaf);
  }
}

TEST(Voxel, SameAsPclOnNegativeAndRandomCoordinates) {
  Cloud c;
  Rng r(11);
  for (int i = 0; i < 20000; ++i) c.points.emplace_back(r.normal(-1, 0.3), r.normal(0.2, 0.1), r.normal(-3, 0.05));
  make_unorganised(c);
  expect_same_as_pcl(c, 0.005f);
}

TEST(Voxel, CentroidColoursLabelsAndMapping) {
  Cloud c;
  c.points = {{0.01f, 0.01f, 0.01f}, {0.03f, 0.03f, 0.03f}, {0.15f, 0.01f, 0.01f}};
  c.colors = {{10, 20, 30}, {30, 40, 51}, {255, 0, 0}};
  c.labels = {7, 7, 3};
  make_unorganised(c);
  const VoxelResult v = voxel_grid(c, {true, 0.1f, 1});
  ASSERT_EQ(v.cloud.size(), 2u);
  EXPECT_LT((v.cloud.points[0] - Eigen::Vector3f(0.02f, 0.02f, 0.02f)).norm(), 1e-7f);
  EXPECT_EQ(v.cloud.colors[0], (Rgb8{20, 30, 41}));  // 40.5 rounds half away from zero
  EXPECT_EQ(v.cloud.labels[1], 3u);
  EXPECT_EQ(v.voxel_of, (std::vector<std::uint32_t>{0, 0, 1}));
  // min_points drops sparse voxels.
  const VoxelResult m = voxel_grid(c, {true, 0.1f, 2});
  ASSERT_EQ(m.cloud.size(), 1u);
  EXPECT_EQ(m.voxel_of[2], VoxelResult::kDropped);
}

// Non-finite points scattered through a cloud larger than one work chunk: they map to kDropped,
// the rest give exactly the voxels of the finite points alone, at one thread and at two.
TEST(Voxel, SkipsNonFinitePointsSameAtAnyThreadCount) {
  Cloud c, finite;
  Rng r(3);
  for (int i = 0; i < 60000; ++i) {
    const Eigen::Vector3f p(r.normal(0.5, 0.2), r.normal(-0.1, 0.2), r.normal(2, 0.1));
    c.points.push_back(i % 7 == 3 ? Eigen::Vector3f(NAN, 0, 0) : p);
    if (i % 7 != 3) finite.points.push_back(p);
  }
  make_unorganised(c), make_unorganised(finite);
  const auto at = [&](const Cloud& in, int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return voxel_grid(in, {true, 0.01f, 2});
  };
  const VoxelResult one = at(c, 1), two = at(c, 2), ref = at(finite, 2);
  ASSERT_GT(ref.cloud.size(), 1000u);
  EXPECT_EQ(one.cloud.points, ref.cloud.points);
  EXPECT_EQ(two.cloud.points, ref.cloud.points);
  EXPECT_EQ(one.voxel_of, two.voxel_of);
  for (std::size_t i = 0, f = 0; i < c.size(); ++i) {
    if (i % 7 == 3) {
      ASSERT_EQ(one.voxel_of[i], VoxelResult::kDropped) << i;
    } else {
      ASSERT_EQ(one.voxel_of[i], ref.voxel_of[f++]) << i;
    }
  }
}

TEST(Voxel, DegenerateInputs) {
  EXPECT_TRUE(voxel_grid(Cloud{}, {true, 0.01f, 1}).cloud.empty());
  Cloud nan;
  nan.points.assign(5, Eigen::Vector3f::Constant(std::nanf("")));
  make_unorganised(nan);
  EXPECT_TRUE(voxel_grid(nan, {true, 0.01f, 1}).cloud.empty());
  Cloud one;
  one.points = {{1, 2, 3}};
  make_unorganised(one);
  EXPECT_EQ(voxel_grid(one, {true, 0.01f, 1}).cloud.size(), 1u);
  EXPECT_THROW(voxel_grid(one, {true, 0.0f, 1}), Error);
  EXPECT_THROW(voxel_grid(one, {true, -1.0f, 1}), Error);
  Cloud huge;
  huge.points = {{-1e6f, -1e6f, -1e6f}, {1e6f, 1e6f, 1e6f}};
  make_unorganised(huge);
  EXPECT_THROW(voxel_grid(huge, {true, 1e-4f, 1}), Error);
  // Coordinates whose cell numbers do not fit an integer are refused, not wrapped.
  Cloud far;
  far.points = {{3e30f, 0, 0}};
  make_unorganised(far);
  EXPECT_THROW(voxel_grid(far, {true, 0.01f, 1}), Error);
}

}  // namespace uwgrasp::cloud
