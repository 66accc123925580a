#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "shapes.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/bvh.hpp"

namespace uwgrasp::grasp {

TEST(Bvh, EveryPointInOneLeafInsideEveryAncestor) {
  Cloud c = test::sphere(5000, 0.2f, Eigen::Vector3f(1, 2, 3));
  const PointBvh b = build_bvh(c.points, 8);
  ASSERT_EQ(b.points.size(), c.size());
  // index is a permutation and points follows it.
  std::vector<std::uint32_t> idx = b.index;
  std::sort(idx.begin(), idx.end());
  for (std::uint32_t i = 0; i < idx.size(); ++i) ASSERT_EQ(idx[i], i);
  for (std::size_t k = 0; k < b.points.size(); ++k) ASSERT_EQ(b.points[k], c.points[b.index[k]]);
  // Walk: children partition their parent; leaves hold at most 8; bounds hold their points.
  std::vector<int> seen(c.size(), 0);
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const BvhNode& n = b.nodes[stack.back()];
    const std::uint32_t i = stack.back();
    stack.pop_back();
    for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
      ASSERT_TRUE(((b.points[k] - n.centre).cwiseAbs() - n.half).maxCoeff() <= 0.0f);
    if (n.leaf()) {
      ASSERT_LE(n.count, 8u);
      for (std::uint32_t k = n.first; k < n.first + n.count; ++k) ++seen[k];
    } else {
      const BvhNode& l = b.nodes[i + 1];
      const BvhNode& r = b.nodes[n.right];
      ASSERT_EQ(l.first, n.first);
      ASSERT_EQ(r.first, l.first + l.count);
      ASSERT_EQ(l.count + r.count, n.count);
      stack.push_back(i + 1);
      stack.push_back(n.right);
    }
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
}

TEST(Bvh, SinglePointAndCoincidentPoints) {
  const std::vector<Eigen::Vector3f> one{Eigen::Vector3f(1, 1, 1)};
  EXPECT_EQ(build_bvh(one).nodes.size(), 1u);
  const std::vector<Eigen::Vector3f> same(100, Eigen::Vector3f(0.5f, 0, 0));
  const PointBvh b = build_bvh(same);
  EXPECT_EQ(b.nodes.front().count, 100u);
}

TEST(Bvh, RejectsEmptyAndNonFinite) {
  EXPECT_THROW(build_bvh(std::vector<Eigen::Vector3f>{}), Error);
  std::vector<Eigen::Vector3f> bad{Eigen::Vector3f(0, 0, 0),
                                   Eigen::Vector3f(std::numeric_limits<float>::quiet_NaN(), 0, 0)};
  EXPECT_THROW(build_bvh(bad), Error);
}

}  // namespace uwgrasp::grasp
