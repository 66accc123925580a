#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "shapes.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/bvh.hpp"

namespace uwgrasp::grasp {

namespace {
Eigen::Vector3f lane_centre(const BvhNode& n, int k) { return {n.cx[k], n.cy[k], n.cz[k]}; }
Eigen::Vector3f lane_half(const BvhNode& n, int k) { return {n.hx[k], n.hy[k], n.hz[k]}; }
bool holds(const BvhNode& n, int k, const Eigen::Vector3f& p, float tolerance = 0.0f) {
  return ((p - lane_centre(n, k)).cwiseAbs() - lane_half(n, k)).maxCoeff() <= tolerance;
}
}  // namespace

TEST(Bvh, EveryPointUnderOneLeafInsideEveryAncestor) {
  for (const int size : {5000, 33, 8, 1}) {
    SCOPED_TRACE(size);
    Cloud c = test::sphere(size, 0.2f, Eigen::Vector3f(1, 2, 3));
    const PointBvh b = build_bvh(c.points);
    ASSERT_EQ(b.points.size(), c.size());
    // index is a permutation and points (and the coordinate arrays) follow it.
    std::vector<std::uint32_t> idx = b.index;
    std::sort(idx.begin(), idx.end());
    for (std::uint32_t i = 0; i < idx.size(); ++i) ASSERT_EQ(idx[i], i);
    ASSERT_EQ(b.x.size() % kLeafPoints, 0u);
    for (std::size_t k = 0; k < b.x.size(); ++k) {
      if (k >= c.size()) {
        ASSERT_TRUE(std::isnan(b.x[k]));  // padding that no test accepts
        continue;
      }
      ASSERT_EQ(b.points[k], c.points[b.index[k]]);
      ASSERT_EQ(Eigen::Vector3f(b.x[k], b.y[k], b.z[k]), b.points[k]);
    }
    ASSERT_EQ(b.levels.back().size(), 1u);  // one root
    // Every child lane holds the points under it, its lanes' boxes sit inside it, and the
    // counts add up to the cloud; missing children are NaN.
    std::uint32_t total = 0;
    for (std::uint32_t level = 0; level < b.levels.size(); ++level)
      for (std::uint32_t j = 0; j < b.levels[level].size(); ++j)
        for (int k = 0; k < 4; ++k) {
          const BvhNode& n = b.levels[level][j];
          const std::uint32_t first = b.first(level, j, k), count = b.count(level, j, k);
          if (count == 0) {
            ASSERT_TRUE(std::isnan(n.cx[k]) && std::isnan(n.hz[k]));
            continue;
          }
          if (level == b.top()) total += count;
          for (std::uint32_t p = first; p < first + count; ++p) ASSERT_TRUE(holds(n, k, b.points[p]));
          if (level == 0) {
            ASSERT_LE(count, kLeafPoints);
            continue;
          }
          const BvhNode& child = b.levels[level - 1][4 * j + std::uint32_t(k)];
          std::uint32_t sum = 0;
          for (int q = 0; q < 4; ++q) sum += b.count(level - 1, 4 * j + std::uint32_t(k), q);
          ASSERT_EQ(sum, count);
          ASSERT_EQ(b.first(level - 1, 4 * j + std::uint32_t(k), 0), first);
          for (int q = 0; q < 4; ++q)
            if (b.count(level - 1, 4 * j + std::uint32_t(k), q) > 0) {
              const Eigen::Vector3f lo = lane_centre(child, q) - lane_half(child, q);
              const Eigen::Vector3f hi = lane_centre(child, q) + lane_half(child, q);
              // Both boxes carry the same padding; allow the rounding of centre +- half.
              ASSERT_TRUE(holds(n, k, lo, 1e-6f) && holds(n, k, hi, 1e-6f));
            }
        }
    EXPECT_EQ(total, c.size());
  }
}

TEST(Bvh, CoincidentPoints) {
  const std::vector<Eigen::Vector3f> same(100, Eigen::Vector3f(0.5f, 0, 0));
  const PointBvh b = build_bvh(same);
  std::uint32_t total = 0;
  for (int k = 0; k < 4; ++k) total += b.count(b.top(), 0, k);
  EXPECT_EQ(total, 100u);
  EXPECT_EQ(b.levels[0].size(), 4u);  // 13 leaves of 8, four to a node
}

TEST(Bvh, RejectsEmptyAndNonFinite) {
  EXPECT_THROW(build_bvh(std::vector<Eigen::Vector3f>{}), Error);
  std::vector<Eigen::Vector3f> bad{Eigen::Vector3f(0, 0, 0),
                                   Eigen::Vector3f(std::numeric_limits<float>::quiet_NaN(), 0, 0)};
  EXPECT_THROW(build_bvh(bad), Error);
}

}  // namespace uwgrasp::grasp
