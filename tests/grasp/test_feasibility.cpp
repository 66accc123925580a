#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "grasp_helpers.hpp"
#include "objects.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/grasp/feasibility.hpp"
#include "uwgrasp/grasp/lanes.hpp"

namespace uwgrasp::grasp {

using test::candidate;
using test::is_collision;
using V = Eigen::Vector3f;

// A 300 mm bar, 30 x 30 mm in section: narrower than the 80 mm aperture.
Cloud bar(float width = 0.03f) {
  return test::solid_box(V(-0.15f, -width / 2, -0.015f), V(0.15f, width / 2, 0.015f), 0.002f);
}

TEST(Feasibility, BarIsGraspableAcrossItsNarrowSideAndNotAlongIt) {
  const Gripper g = make_gripper({});
  const Cloud c = bar();
  for (float x = -0.1f; x <= 0.1f; x += 0.025f) {
    SCOPED_TRACE(x);
    const Check across = test::check_one(c, g, candidate(V(x, 0, 0), V(0, 0, -1), V(0, 1, 0)));
    ASSERT_TRUE(across.feasible()) << reject_name(across.reason);
    EXPECT_NEAR(across.width, 0.03f, 1e-5f);
    EXPECT_NEAR(c.points[across.left].y(), -0.015f, 1e-6f);  // contacts on the side faces
    EXPECT_NEAR(c.points[across.right].y(), 0.015f, 1e-6f);
    EXPECT_GT(across.inliers, 50u);
    const Check along = test::check_one(c, g, candidate(V(x, 0, 0), V(0, 0, -1), V(1, 0, 0)));
    EXPECT_TRUE(along.reason == Reject::collision_left_finger ||
                along.reason == Reject::collision_right_finger)
        << reject_name(along.reason);
  }
  // Off-centre across the bar: still feasible while the bar stays between the fingers.
  EXPECT_TRUE(test::check_one(c, g, candidate(V(0, 0.02f, 0), V(0, 0, -1), V(0, 1, 0))).feasible());
  EXPECT_TRUE(is_collision(
      test::check_one(c, g, candidate(V(0, 0.045f, 0), V(0, 0, -1), V(0, 1, 0))).reason));
  // Too deep: the palm lands on the bar.
  EXPECT_EQ(test::check_one(c, g, candidate(V(0, 0, -0.03f), V(0, 0, -1), V(0, 1, 0))).reason,
            Reject::collision_palm);
  // Far away: nothing in the closing region.
  EXPECT_EQ(test::check_one(c, g, candidate(V(0, 0, 0.5f), V(0, 0, -1), V(0, 1, 0))).reason,
            Reject::empty);
}

TEST(Feasibility, PlateWiderThanTheApertureEdgeOnGivesOnlyCollisions) {
  const Gripper g = make_gripper({});
  const Cloud plate = test::solid_box(V(-0.1f, -0.1f, -0.005f), V(0.1f, 0.1f, 0.005f), 0.002f);
  const PointBvh bvh = build_bvh(plate.points);
  std::vector<Candidate> across, thickness;
  Rng rng(7);
  for (int i = 0; i < 400; ++i) {
    const float depth = -0.1f + float(rng.uniform() * 0.05 - 0.02);  // the edge is at x = -0.1
    const float y = float(rng.uniform() * 0.1 - 0.05);
    const V tilt(0, float(rng.normal() * 0.05), float(rng.normal() * 0.05));
    across.push_back(candidate(V(depth, y, 0), V(1, 0, 0) + tilt, V(0, 1, 0)));
    thickness.push_back(candidate(V(depth, y, 0), V(1, 0, 0), V(0, 0, 1)));
  }
  const auto a = check_candidates(bvh, g, across);
  for (const Check& k : a) EXPECT_TRUE(is_collision(k.reason)) << reject_name(k.reason);
  // The same edge closed across the 10 mm thickness is graspable.
  const auto t = check_candidates(bvh, g, thickness);
  EXPECT_GT(count_rejections(t)[0], 300u);
}

TEST(Feasibility, WidthAtClosureLimits) {
  GripperConfig cfg;  // accepts up to 80 - 2 * 5 = 70 mm
  const Gripper g = make_gripper(cfg);
  const auto top = [&](const Cloud& c) {
    return test::check_one(c, g, candidate(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0)));
  };
  EXPECT_EQ(top(bar(0.075f)).reason, Reject::too_wide);
  EXPECT_TRUE(top(bar(0.06f)).feasible());
  cfg.min_aperture = 0.02f;
  const Gripper narrow = make_gripper(cfg);
  EXPECT_EQ(test::check_one(bar(0.01f), narrow, candidate(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0))).reason,
            Reject::too_narrow);
}

// The BVH walk and the thesis's every-point check agree on a real-sized object; the counts of
// every reason add up to the number of candidates.
TEST(Feasibility, HierarchyMatchesBruteForceAndCountsAddUp) {
  const auto obj = fixtures::render_object(fixtures::Object::barbell, {}, 20000);
  const auto& pts = obj.cloud.points;
  const Gripper g = make_gripper({});
  SamplerConfig sc;
  const auto cand = sample_normal(pts, sc, Eigen::Matrix3d::Identity(), 3, 1500);
  const PointBvh bvh = build_bvh(pts);
  const auto checks = check_candidates(bvh, g, cand);
  std::size_t feasible = 0;
  std::vector<std::uint32_t> idx;
  for (std::size_t i = 0; i < cand.size(); ++i) {
    const Check b = check_brute(pts, g, cand[i]);
    const Check& h = checks[i];
    ASSERT_EQ(is_collision(h.reason), is_collision(b.reason)) << i;
    if (is_collision(b.reason)) {
      // The part named holds a point (the walk and the probe points may name another part than
      // the brute force's first point does).
      const Box& part = g.solids[std::size_t(int(h.reason) - int(Reject::collision_left_finger))];
      const lanes::Frame4 to_gripper(cand[i].rotation.transpose(), cand[i].position);
      ASSERT_TRUE(std::any_of(pts.begin(), pts.end(), [&](const auto& p) { return part.contains(to_gripper.point(p)); }))
          << i << " " << reject_name(h.reason);
      continue;
    }
    ASSERT_EQ(h.reason, b.reason) << i;
    ASSERT_EQ(h.inliers, b.inliers) << i;
    // The hierarchy's closing region is the brute force's, as a set (its order is the walk's).
    closing_indices(bvh, g, cand[i], idx);
    std::sort(idx.begin(), idx.end());
    ASSERT_EQ(idx, closing_points(pts, g, cand[i])) << i;
    ASSERT_EQ(h.inliers, idx.size()) << i;
    if (h.inliers == 0) continue;
    ASSERT_EQ(h.nearest, b.nearest) << i;
    ASSERT_EQ(h.left, b.left) << i;
    ASSERT_EQ(h.right, b.right) << i;
    ASSERT_EQ(h.width, b.width) << i;
    feasible += h.feasible();
  }
  EXPECT_GT(feasible, 10u);  // the comparison covered feasible candidates too
  const RejectCounts counts = count_rejections(checks);
  EXPECT_EQ(std::accumulate(counts.begin(), counts.end(), std::size_t(0)), cand.size());
  EXPECT_EQ(counts[0], feasible);
}

}  // namespace uwgrasp::grasp
