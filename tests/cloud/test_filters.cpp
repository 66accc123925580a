#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cfloat>
#include <random>

#include "shapes.hpp"
#include "uwgrasp/cloud/filters.hpp"

namespace uwgrasp::cloud {

TEST(Filters, RemoveInvalidKeepsPixelIndicesOfAnOrganisedCloud) {
  Cloud c;
  c.width = 4, c.height = 2;
  for (int i = 0; i < 8; ++i) c.points.emplace_back(float(i), 0.f, 1.f);
  c.points[1].x() = std::nanf("");
  c.points[6].z() = INFINITY;
  c.colors.assign(8, {1, 2, 3});
  const Filtered f = remove_invalid(c);
  EXPECT_EQ(f.indices, (std::vector<std::uint32_t>{0, 2, 3, 4, 5, 7}));
  EXPECT_EQ(f.cloud.size(), 6u);
  EXPECT_EQ(f.cloud.colors.size(), 6u);
  EXPECT_EQ(f.cloud.points[1].x(), 2.f);
  // Row and column of a kept point are recoverable from the input width.
  EXPECT_EQ(f.indices[4] / c.width, 1u);
  EXPECT_EQ(f.indices[4] % c.width, 1u);
}

TEST(Filters, AllNanAndEmpty) {
  Cloud c;
  c.points.assign(10, Eigen::Vector3f::Constant(std::nanf("")));
  make_unorganised(c);
  EXPECT_TRUE(remove_invalid(c).cloud.empty());
  EXPECT_TRUE(remove_invalid(Cloud{}).cloud.empty());
}

TEST(Filters, RangeCropMeasuresFromTheViewpoint) {
  Cloud c;
  for (float z : {0.5f, 3.0f, 5.99f, 6.01f, 10.f}) c.points.emplace_back(0.f, 0.f, z);
  make_unorganised(c);
  RangeConfig cfg;  // 6 m limit of thesis 7.4.1
  EXPECT_EQ(crop_range(c, cfg).indices, (std::vector<std::uint32_t>{0, 1, 2}));
  cfg.min = 1.0f;
  EXPECT_EQ(crop_range(c, cfg).indices, (std::vector<std::uint32_t>{1, 2}));
  c.viewpoint = {0, 0, 5};
  cfg.min = 0, cfg.max = 2;
  EXPECT_EQ(crop_range(c, cfg).indices, (std::vector<std::uint32_t>{1, 2, 3}));
}

// Over many chunks, with every kind of non-finite value and the finite extremes: the filters
// keep exactly what a plain loop keeps, in order, at 1 and 2 threads; a cloud with nothing to
// drop comes back whole (unorganised).
TEST(Filters, ManyChunksMatchAPlainLoopAtAnyThreadCount) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-8.0f, 8.0f);
  const float odd[] = {std::nanf(""), INFINITY, -INFINITY, FLT_MAX, -FLT_MAX, FLT_MIN / 4, -0.0f};
  Cloud c;
  c.width = 1000, c.height = 70;
  for (std::size_t i = 0; i < 70000; ++i) {
    Eigen::Vector3f p(u(rng), u(rng), u(rng));
    if (i % 37 == 0) p[std::ptrdiff_t(i % 3)] = odd[(i / 37) % 7];
    c.points.push_back(p);
    c.colors.push_back({std::uint8_t(i), std::uint8_t(i >> 8), 7});
  }
  RangeConfig rc;
  rc.min = 1.0f, rc.max = 9.0f;
  std::vector<std::uint32_t> finite, ranged;
  for (std::uint32_t i = 0; i < c.size(); ++i) {
    const Eigen::Vector3f& p = c.points[i];
    const bool f = std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
    if (f) finite.push_back(i);
    if (f && p.squaredNorm() >= 1.0f && p.squaredNorm() <= 81.0f) ranged.push_back(i);
  }
  ASSERT_LT(finite.size(), c.size());
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    const Filtered f = remove_invalid(c);
    EXPECT_EQ(f.indices, finite);
    ASSERT_EQ(f.cloud.size(), finite.size());
    EXPECT_EQ(f.cloud.points[100], c.points[finite[100]]);
    EXPECT_EQ(f.cloud.colors[100], c.colors[finite[100]]);
    EXPECT_EQ(crop_range(c, rc).indices, ranged);
    EXPECT_EQ(in_range(c, rc), ranged);
    // Nothing to drop: the whole cloud, unorganised.
    const Filtered all = remove_invalid(f.cloud);
    EXPECT_EQ(all.indices.size(), f.cloud.size());
    EXPECT_EQ(all.cloud.points, f.cloud.points);
    EXPECT_EQ(all.cloud.colors, f.cloud.colors);
    Cloud organised = f.cloud;
    organised.width = 2, organised.height = std::uint32_t(organised.size() / 2);
    organised.points.resize(std::size_t(organised.width) * organised.height);
    organised.colors.resize(organised.points.size());
    const Filtered whole = keep_if(organised, std::vector<char>(organised.size(), 1));
    EXPECT_EQ(whole.cloud.points, organised.points);
    EXPECT_EQ(whole.cloud.width, organised.size());
    EXPECT_EQ(whole.cloud.height, 1u);
  }
}

}  // namespace uwgrasp::cloud
