#include <gtest/gtest.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/region_growing.h>
#include <tbb/global_control.h>

#include <map>

#include "pcl_convert.hpp"
#include "shapes.hpp"
#include "uwgrasp/cloud/filters.hpp"
#include "uwgrasp/cloud/normals.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/pcd.hpp"
#include "uwgrasp/segment/region_growing.hpp"

namespace uwgrasp::segment {

namespace {
// Mean over reference segments of the best IoU with any of our segments.
double mean_best_iou(const std::vector<std::vector<std::uint32_t>>& ref,
                     const std::vector<std::int32_t>& ours, std::size_t nours) {
  double sum = 0;
  for (const auto& r : ref) {
    std::map<std::int32_t, std::size_t> inter;
    for (auto i : r) ++inter[ours[i]];
    std::vector<std::size_t> size(nours, 0);
    for (auto l : ours)
      if (l >= 0) ++size[std::size_t(l)];
    double best = 0;
    for (auto [l, n] : inter)
      if (l >= 0) best = std::max(best, double(n) / double(r.size() + size[std::size_t(l)] - n));
    sum += best;
  }
  return ref.empty() ? 1.0 : sum / double(ref.size());
}
}  // namespace

TEST(RegionGrowing, TwoSeparateBoxesFaceByFace) {
  Cloud c = test::box_surface({0, 0, 1}, {0.1f, 0.1f, 1.1f}, 0.005f);
  test::append(c, test::box_surface({0.3f, 0, 1}, {0.4f, 0.1f, 1.1f}, 0.005f));
  c.viewpoint = {0.2f, 0.05f, 0.0f};
  cloud::compute_normals(c, {10, 0});
  RegionConfig r;
  r.k = 10;
  r.min_size = 100;
  const Segmentation s = grow_regions(c, r, {});
  // Each flat face is one region (edges have high curvature and do not seed across corners).
  ASSERT_GE(s.segments.size(), 2u);
  for (const auto& seg : s.segments) {
    const float x0 = c.points[seg.front()].x();
    for (auto i : seg) EXPECT_EQ(c.points[i].x() < 0.2f, x0 < 0.2f) << "region spans two boxes";
  }
}

TEST(RegionGrowing, ASphereAndAPlaneAreTwoSegments) {
  Cloud c = test::plane_grid(100, 1.0f, 2.0f);
  test::append(c, test::sphere(3000, 0.1f, {0, 0, 1.5f}));
  cloud::compute_normals(c, {});
  const Segmentation s = grow_regions(c, {}, {});
  ASSERT_EQ(s.segments.size(), 2u);
  EXPECT_EQ(s.segments[0].size(), 10000u);  // the plane has the lowest curvature: seeded first
  EXPECT_GT(s.segments[1].size(), 1400u);   // the visible half of the sphere and more
}

// Regions are numbered in seed order, which is ascending curvature: a patch whose lowest
// curvature is negative (a rounding artefact of the eigen solver) or -0 seeds before one at +0,
// and equal curvatures seed by index.
TEST(RegionGrowing, SeedsByAscendingCurvatureIncludingNegativeAndSignedZero) {
  const auto patches = [](float a, float b, float c) {
    Cloud cloud = test::plane_grid(20, 0.1f, 1.0f);
    for (const float dx : {0.5f, 1.0f}) {
      Cloud p = test::plane_grid(20, 0.1f, 1.0f);
      for (auto& q : p.points) q.x() += dx;
      test::append(cloud, p);
    }
    cloud.normals.assign(cloud.size(), Eigen::Vector3f(0, 0, 1));
    cloud.curvature.assign(cloud.size(), 0.01f);
    cloud.curvature[399] = a, cloud.curvature[400 + 7] = b, cloud.curvature[800 + 3] = c;
    RegionConfig r;
    r.min_size = 10;
    const Segmentation s = grow_regions(cloud, r, {});
    EXPECT_EQ(s.segments.size(), 3u);
    std::vector<std::int32_t> first;  // the segment of each patch, in patch order
    for (const std::uint32_t i : {0u, 400u, 800u}) first.push_back(s.label[i]);
    return first;
  };
  EXPECT_EQ(patches(0.0f, -1e-9f, 0.005f), (std::vector<std::int32_t>{1, 0, 2}));
  EXPECT_EQ(patches(0.0f, -0.0f, 0.005f), (std::vector<std::int32_t>{0, 1, 2}));  // tie: index
  EXPECT_EQ(patches(0.002f, 0.003f, -0.5f), (std::vector<std::int32_t>{1, 2, 0}));
}

TEST(RegionGrowing, MatchesPclRegionGrowingOnARealScan) {
  UWGRASP_DATA_OR_SKIP(path, "clouds/milk_color.pcd");
  Cloud c = cloud::remove_invalid(io::load_cloud(path)).cloud;
  cloud::compute_normals(c, {30, 0});
  RegionConfig r;
  r.k = 30, r.angle_deg = 3.0f, r.curvature = 1.0f, r.distance = 0.0f, r.min_size = 50;
  const Segmentation ours = grow_regions(c, r, {});
  pcl::RegionGrowing<pcl::PointXYZ, pcl::Normal> rg;
  rg.setInputCloud(test::to_pcl_xyz(c));
  rg.setInputNormals(test::to_pcl_normals(c));
  rg.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
  rg.setNumberOfNeighbours(30);
  rg.setSmoothnessThreshold(3.0f / 180.0f * float(M_PI));
  rg.setCurvatureThreshold(1.0f);
  rg.setMinClusterSize(50);
  std::vector<pcl::PointIndices> ref_clusters;
  rg.extract(ref_clusters);
  std::vector<std::vector<std::uint32_t>> ref;
  for (const auto& cl : ref_clusters) ref.emplace_back(cl.indices.begin(), cl.indices.end());
  ASSERT_FALSE(ref.empty());
  // Same algorithm; only ties in the curvature sort may order seeds differently.
  EXPECT_GE(mean_best_iou(ref, ours.label, ours.segments.size()), 0.97);
  EXPECT_NEAR(double(ours.segments.size()), double(ref.size()), 0.1 * double(ref.size()) + 1);
}

TEST(RegionGrowing, ColourSplitsACoplanarPatchAndMergingJoinsSameColour) {
  // One plane: left half red, right half blue; both halves split by a 1 cm gap on the left.
  Cloud c;
  for (float x = -0.5f; x < 0.5f; x += 0.005f)
    for (float y = -0.2f; y < 0.2f; y += 0.005f) {
      if (x > -0.3f && x < -0.29f) continue;  // gap
      c.points.emplace_back(x, y, 1.0f);
      c.colors.push_back(x < 0 ? Rgb8{200, 20, 20} : Rgb8{20, 20, 200});
    }
  make_unorganised(c);
  cloud::compute_normals(c, {});
  RegionConfig r;
  r.distance = 0.008f;  // the gap breaks growth
  ColorConfig col;
  col.enabled = true;
  col.merge_distance = 0.0f;
  const Segmentation no_merge = grow_regions(c, r, col);
  EXPECT_EQ(no_merge.segments.size(), 3u);  // red | red | blue
  col.merge_distance = 0.02f;               // the gap is bridged by the merge step
  const Segmentation merged = grow_regions(c, r, col);
  ASSERT_EQ(merged.segments.size(), 2u);
  for (const auto& seg : merged.segments)
    for (auto i : seg) EXPECT_EQ(c.colors[i], c.colors[seg.front()]);
  ColorConfig off;
  EXPECT_EQ(grow_regions(c, r, off).segments.size(), 2u);  // geometry alone: gap only
}

TEST(RegionGrowing, SmallRegionsMergeIntoTheirNeighbourWithColour) {
  Cloud c = test::plane_grid(60, 0.6f, 1.0f);
  test::paint(c, {100, 100, 100});
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c.points[i].norm() < 1.0f + 1e-6f && std::abs(c.points[i].x()) < 0.02f && std::abs(c.points[i].y()) < 0.02f)
      c.colors[i] = {250, 250, 0};  // a small yellow blob (< min_size)
  cloud::compute_normals(c, {});
  ColorConfig col;
  col.enabled = true;
  const Segmentation s = grow_regions(c, {}, col);
  ASSERT_EQ(s.segments.size(), 1u);
  EXPECT_EQ(s.segments[0].size(), c.size());
}

TEST(RegionGrowing, DeterministicAcrossThreadCounts) {
  UWGRASP_DATA_OR_SKIP(path, "clouds/milk_color.pcd");
  Cloud c = cloud::remove_invalid(io::load_cloud(path)).cloud;
  cloud::compute_normals(c, {});
  Segmentation a, b;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    a = grow_regions(c, {}, {});
  }
  {
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    b = grow_regions(c, {}, {});
  }
  EXPECT_EQ(a.label, b.label);
}

TEST(RegionGrowing, DegenerateInputs) {
  Cloud c;
  EXPECT_TRUE(grow_regions(c, {}, {}).segments.empty());
  c.points = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  make_unorganised(c);
  EXPECT_THROW(grow_regions(c, {}, {}), Error);  // no normals
  Cloud two;
  two.points = {{0, 0, 1}, {1, 0, 1}};
  make_unorganised(two);
  cloud::compute_normals(two, {});  // NaN normals: nobody seeds
  EXPECT_TRUE(grow_regions(two, {}, {}).segments.empty());
  ColorConfig col;
  col.enabled = true;
  EXPECT_THROW(grow_regions(two, {}, col), Error);  // colour without colours
}

}  // namespace uwgrasp::segment
