#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "uwgrasp/core/rng.hpp"

namespace uwgrasp {

TEST(Rng, SameSeedAndStreamSameSequence) {
  Rng a(42, 7), b(42, 7), c(42, 8), d(43, 7);
  bool differs_c = false, differs_d = false;
  for (int i = 0; i < 100; ++i) {
    const auto x = a.next();
    EXPECT_EQ(x, b.next());
    differs_c |= x != c.next();
    differs_d |= x != d.next();
  }
  EXPECT_TRUE(differs_c);
  EXPECT_TRUE(differs_d);
}

TEST(Rng, UniformAndBelowStayInRange) {
  Rng r(1);
  std::set<std::uint64_t> seen;
  for (int i = 0; i < 10000; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    const auto k = r.below(7);
    ASSERT_LT(k, 7u);
    seen.insert(k);
  }
  EXPECT_EQ(seen.size(), 7u);
}

TEST(Rng, NormalHasTheRequestedMoments) {
  Rng r(9);
  const int n = 200000;
  double s = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.normal(2.0, 0.5);
    s += x, s2 += x * x;
  }
  const double mean = s / n, sd = std::sqrt(s2 / n - mean * mean);
  EXPECT_NEAR(mean, 2.0, 0.01);   // 4 standard errors of the mean
  EXPECT_NEAR(sd, 0.5, 0.005);
}

}  // namespace uwgrasp
