#include <gtest/gtest.h>

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

}  // namespace uwgrasp::cloud
