#include <gtest/gtest.h>

#include "shapes.hpp"
#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp {

TEST(Cloud, SelectKeepsEveryAttributeInIndexOrder) {
  Cloud c;
  for (int i = 0; i < 5; ++i) {
    c.points.emplace_back(float(i), 0.f, 0.f);
    c.normals.emplace_back(0.f, 0.f, 1.f);
    c.curvature.push_back(0.1f * float(i));
    c.colors.push_back({std::uint8_t(i), 0, 0});
    c.labels.push_back(std::uint32_t(10 + i));
  }
  c.width = 5;
  c.viewpoint = {1, 2, 3};
  const std::vector<std::uint32_t> idx{4, 1};
  const Cloud s = select(c, idx);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.points[0].x(), 4.f);
  EXPECT_EQ(s.labels[1], 11u);
  EXPECT_FLOAT_EQ(s.curvature[0], 0.4f);
  EXPECT_EQ(s.colors[1].r, 1);
  EXPECT_EQ(s.width, 2u);
  EXPECT_EQ(s.height, 1u);
  EXPECT_EQ(s.viewpoint, c.viewpoint);
}

TEST(Cloud, InconsistentAttributesAreRejectedByName) {
  Cloud c;
  c.points.resize(3);
  c.width = 3;
  EXPECT_NO_THROW(check_consistent(c, "x"));
  c.normals.resize(2);
  try {
    check_consistent(c, "my.pcd");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("normals"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("my.pcd"), std::string::npos);
  }
  c.normals.clear();
  c.width = 2;
  EXPECT_THROW(check_consistent(c, "x"), Error);
}

TEST(Cloud, CentroidAndCovarianceOfABoxSurfaceAreAnalytic) {
  // Corners of a 2 x 4 x 6 box centred at (1, 1, 1): covariance diag(1, 4, 9).
  Cloud c;
  for (int i = 0; i < 8; ++i)
    c.points.emplace_back(1 + ((i & 1) ? 1.f : -1.f), 1 + ((i & 2) ? 2.f : -2.f),
                          1 + ((i & 4) ? 3.f : -3.f));
  const Eigen::Vector3d m = centroid(c);
  EXPECT_NEAR((m - Eigen::Vector3d(1, 1, 1)).norm(), 0.0, 1e-12);
  const Eigen::Matrix3d cov = covariance(c, m);
  EXPECT_NEAR((cov - Eigen::Vector3d(1, 4, 9).asDiagonal().toDenseMatrix()).norm(), 0, 1e-12);
}

TEST(Cloud, FiniteCheck) {
  EXPECT_TRUE(is_finite({1, 2, 3}));
  EXPECT_FALSE(is_finite({std::nanf(""), 0, 0}));
  EXPECT_FALSE(is_finite({0, INFINITY, 0}));
}

}  // namespace uwgrasp
