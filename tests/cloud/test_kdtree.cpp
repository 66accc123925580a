#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "shapes.hpp"
#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

namespace {
Cloud random_cloud(int n, std::uint64_t seed) {
  Cloud c;
  Rng r(seed);
  for (int i = 0; i < n; ++i) c.points.emplace_back(r.uniform(), r.uniform(), 0.2 * r.uniform());
  make_unorganised(c);
  return c;
}
std::vector<Eigen::Vector3f> sub_of(const Cloud& c, std::size_t n) {
  return {c.points.begin(), c.points.begin() + static_cast<std::ptrdiff_t>(n)};
}
}  // namespace

TEST(KdTree, KnnMatchesBruteForce) {
  const Cloud c = random_cloud(3000, 1);
  const KdTree tree(c.points);
  Rng r(2);
  for (int q = 0; q < 200; ++q) {
    const Eigen::Vector3f p(r.uniform(), r.uniform(), 0.2 * r.uniform());
    std::vector<float> brute;
    for (const auto& x : c.points) brute.push_back((x - p).squaredNorm());
    std::sort(brute.begin(), brute.end());
    std::uint32_t idx[12];
    float d2[12];
    ASSERT_EQ(tree.knn(p, 12, idx, d2), 12u);
    for (int j = 0; j < 12; ++j) {
      EXPECT_FLOAT_EQ(d2[j], brute[j]);
      EXPECT_FLOAT_EQ((c.points[idx[j]] - p).squaredNorm(), d2[j]);
    }
  }
}

TEST(KdTree, RadiusMatchesBruteForce) {
  const Cloud c = random_cloud(2000, 3);
  const KdTree tree(c.points);
  std::vector<std::pair<std::uint32_t, float>> hits;
  for (std::size_t q = 0; q < 100; ++q) {
    const Eigen::Vector3f p = c.points[q * 7];
    tree.radius(p, 0.05f, hits);
    std::vector<std::uint32_t> brute;
    for (std::size_t i = 0; i < c.size(); ++i)
      if ((c.points[i] - p).squaredNorm() <= 0.05f * 0.05f) brute.push_back(std::uint32_t(i));
    std::vector<std::uint32_t> got;
    for (auto& h : hits) got.push_back(h.first);
    EXPECT_TRUE(std::is_sorted(hits.begin(), hits.end(),
                               [](auto& a, auto& b) { return a.second < b.second; }));
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, brute);
  }
}

// any_within(q, r) is "the nearest point's squared distance <= r * r", the test gather_parts
// made with knn(q, 1): at random radii, at the nearest's own distance and one float step either
// side of it (where the pruning's bound is tested), and at 0 on a point of the cloud.
TEST(KdTree, AnyWithinIsTheNearestWithinTheRadius) {
  const Cloud c = random_cloud(3000, 5);
  const KdTree tree(c.points);
  Rng r(6);
  int near = 0, far = 0;
  for (int q = 0; q < 300; ++q) {
    const Eigen::Vector3f p(r.uniform(), r.uniform(), 0.2 * r.uniform());
    std::uint32_t idx = 0;
    float d2 = 0.0f;
    ASSERT_EQ(tree.knn(p, 1, &idx, &d2), 1u);
    const float at = std::sqrt(d2);
    for (const float radius :
         {float(0.05 * r.uniform()), at, std::nextafter(at, 0.0f), std::nextafter(at, 1.0f)}) {
      const bool expected = d2 <= radius * radius;
      EXPECT_EQ(tree.any_within(p, radius), expected) << "query " << q << " radius " << radius;
      (expected ? near : far) += 1;
    }
    EXPECT_TRUE(tree.any_within(c.points[std::size_t(q)], 0.0f));
  }
  EXPECT_GT(near, 300);  // both answers were asked for
  EXPECT_GT(far, 100);
  EXPECT_FALSE(tree.any_within({0.5f, 0.5f, 0.1f}, -1.0f));
  EXPECT_FALSE(tree.any_within({0.5f, 0.5f, 0.1f}, std::nanf("")));
  Cloud empty;
  EXPECT_FALSE(KdTree(empty.points).any_within({0, 0, 0}, 10.0f));
}

TEST(KdTree, KnnAllIsIndependentOfThreadsAndFindsSelfFirst) {
  const Cloud c = random_cloud(5000, 4);
  const KdTree tree(c.points);
  const Neighbours nb = knn_all(tree, c.points, 8);
  for (std::size_t i = 0; i < c.size(); i += 97) {
    ASSERT_EQ(nb.count[i], 8u);
    EXPECT_EQ(nb.sq_dists[i * 8], 0.0f);
  }
}

// Oracle: a fresh search over the subset alone. Random subsets from nearly all points to a
// handful leave many rows short (searched in a tree of the subset); removing the 80 points
// nearest point 0 but point 0 leaves a few rows short by many points (widened in the full tree;
// point 0's own row several times).
TEST(KdTree, RestrictedListsMatchASearchOverTheSubset) {
  const Cloud c = random_cloud(4000, 5);
  const KdTree tree(c.points);
  const Neighbours all = knn_all(tree, c.points, 12);
  std::vector<std::uint32_t> ball(80);
  std::vector<float> ball_d2(80);
  tree.knn(c.points[0], 80, ball.data(), ball_d2.data());
  Rng r(6);
  for (double share : {-1.0, 0.97, 0.5, 0.05, 0.002}) {
    std::vector<std::uint32_t> kept;
    Cloud sub;
    for (std::uint32_t i = 0; i < c.size(); ++i) {
      const bool in_ball = std::find(ball.begin(), ball.end(), i) != ball.end();
      if (share < 0 ? !in_ball || i == 0 : r.uniform() < share)
        kept.push_back(i), sub.points.push_back(c.points[i]);
    }
    for (std::size_t k : {std::size_t{10}, std::size_t{30}}) {
      const Neighbours got = restrict_neighbours(tree, all, kept, k);
      const KdTree sub_tree(sub.points);
      const Neighbours ref = knn_all(sub_tree, sub.points, std::min(k, sub.size()));
      ASSERT_EQ(got.k, ref.k) << share;
      for (std::size_t j = 0; j < kept.size(); ++j) {
        ASSERT_EQ(got.count[j], ref.count[j]) << "share " << share << " row " << j;
        for (std::size_t m = 0; m < got.count[j]; ++m) {
          EXPECT_EQ(got.dists_of(j)[m], ref.dists_of(j)[m]) << "share " << share << " row " << j;
          EXPECT_FLOAT_EQ((sub.points[got.of(j)[m]] - sub.points[j]).squaredNorm(),
                          got.dists_of(j)[m]);
        }
      }
    }
  }
  EXPECT_EQ(restrict_neighbours(tree, all, {}, 10).count.size(), 0u);
  EXPECT_THROW(restrict_neighbours(tree, knn_all(tree, sub_of(c, 10), 3), {}, 3), Error);
}

TEST(KdTree, DegenerateInputs) {
  Cloud empty;
  const KdTree t0(empty.points);
  std::uint32_t idx[3];
  float d2[3];
  EXPECT_EQ(t0.knn({0, 0, 0}, 3, idx, d2), 0u);
  Cloud one;
  one.points.emplace_back(1, 2, 3);
  const KdTree t1(one.points);
  EXPECT_EQ(t1.knn({0, 0, 0}, 3, idx, d2), 1u);
  Cloud bad;
  bad.points.emplace_back(std::nanf(""), 0, 0);
  EXPECT_THROW(KdTree t(bad.points), Error);
}

}  // namespace uwgrasp::cloud
