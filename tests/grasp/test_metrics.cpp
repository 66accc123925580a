#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "grasp_helpers.hpp"
#include "shapes.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/metrics.hpp"
#include "uwgrasp/grasp/score.hpp"

namespace uwgrasp::grasp {

using V = Eigen::Vector3f;
constexpr double kPi = std::numbers::pi;

namespace {
// Scores one hand-placed candidate on a cloud with normals (frames: identity).
Grasp score_one(const Cloud& c, const Candidate& k, const ScoreConfig& s = {}) {
  const Gripper g = make_gripper({});
  const Check check = test::check_one(c, g, k);
  EXPECT_TRUE(check.feasible()) << reject_name(check.reason);
  Frames f;
  f.level_from_camera = Pose::Identity();
  f.body_from_gripper = Pose::Identity();
  return score_candidate(c.points, c.normals, k, check, f, s, 135);
}
}  // namespace

// q_n: 1 approaching along the plane's normal, 0 approaching parallel to the plane (6.2).
TEST(Metrics, NormalAlignmentOnAPlanePatch) {
  Cloud patch = test::plane_grid(30, 0.03f, 0.0f);
  patch.normals.assign(patch.size(), V(0, 0, 1));
  EXPECT_NEAR(score_one(patch, test::candidate(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0))).scores.normal, 1.0, 1e-6);
  EXPECT_NEAR(score_one(patch, test::candidate(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0))).scores.normal, 0.0, 1e-6);
  const double tilted =
      score_one(patch, test::candidate(V(0, 0, 0), V(std::sin(0.5f), 0, -std::cos(0.5f)), V(0, 1, 0))).scores.normal;
  EXPECT_NEAR(tilted, std::cos(0.5), 1e-5);
  // The erratum: a cosine, so the sense of either vector does not matter.
  EXPECT_DOUBLE_EQ(alignment({0, 0, 1}, {0, 0, -2}), 1.0);
  EXPECT_DOUBLE_EQ(alignment({0, 0, 0}, {0, 0, 1}), 0.0);
}

// Eq. 6.3 in both forms, and eq. 6.4's weighting.
TEST(Metrics, OrientationTermsAtKnownAngles) {
  const auto M = OrientationForm::monotone, T = OrientationForm::thesis;
  EXPECT_DOUBLE_EQ(orientation_term(0, M), 1.0);
  EXPECT_NEAR(orientation_term(kPi / 6, M), 0.5, 1e-12);
  EXPECT_NEAR(orientation_term(-kPi / 6, T), 0.5, 1e-12);
  EXPECT_NEAR(orientation_term(kPi / 2, M), 0.0, 1e-12);
  EXPECT_NEAR(orientation_term(2 * kPi / 3, T), 1 - std::sin(2 * kPi / 3), 1e-12);  // rises again
  EXPECT_EQ(orientation_term(2 * kPi / 3, M), 0.0);                                 // does not
  EXPECT_NEAR(orientation_term(kPi, T), 1.0, 1e-12);
  EXPECT_EQ(orientation_term(kPi, M), 0.0);
  EXPECT_NEAR(orientation_term(2 * kPi + kPi / 6, M), 0.5, 1e-12);  // wrapped
  OrientationConfig c;  // Table 8.5: 0.45, 0.45, 0.1
  EXPECT_NEAR(orientation_score({kPi / 6, 0, kPi / 2}, c), 0.45 * 0.5 + 0.45, 1e-12);
  c.roll = c.pitch = c.yaw = 1.0;  // normalised: weights need not sum to 1
  EXPECT_NEAR(orientation_score({kPi / 6, 0, 0}, c), 2.5 / 3, 1e-12);
  c.roll = c.pitch = c.yaw = 0.0;
  EXPECT_THROW(orientation_score({0, 0, 0}, c), Error);
}

// q_cl = q_cr = 1 on a box approached squarely (6.4): contacts on opposite faces, the line
// between them along both normals; the grasp is antipodal for any mu.
TEST(Metrics, ContactAlignmentOnABoxApproachedSquarely) {
  const Cloud box = test::solid_box(V(-0.1f, -0.02f, -0.02f), V(0.1f, 0.02f, 0.02f), 0.002f);
  // Just below the top face, so the point nearest the gripper position is on it.
  const Grasp g = score_one(box, test::candidate(V(0, 0, 0.015f), V(0, 0, -1), V(0, 1, 0)));
  EXPECT_NEAR(g.scores.contact_left, 1.0, 1e-6);
  EXPECT_NEAR(g.scores.contact_right, 1.0, 1e-6);
  EXPECT_NEAR(g.width, 0.04, 1e-6);
  EXPECT_TRUE(g.friction.ok);
  EXPECT_NEAR(g.friction.mu_required, 0.0, 1e-6);
  EXPECT_NEAR(g.scores.normal, 1.0, 1e-6);  // the top face under the gripper
  EXPECT_NEAR(g.scores.orientation, orientation_score(g.vehicle_rpy, {}), 1e-12);
  const double q_i = std::min(1.0, double(g.inliers) / 135.0);
  EXPECT_DOUBLE_EQ(g.scores.inliers, q_i);
  EXPECT_NEAR(g.scores.total, g.scores.normal + g.scores.orientation + 2.0 + q_i, 1e-9);
}

// The friction-cone test flips where the contact normals leave the cone: tan(angle) = mu.
TEST(Metrics, FrictionConeFlipsAtTheExpectedAngle) {
  const double mu = 0.3, edge = std::atan(mu);
  for (double angle : {edge - 0.01, edge + 0.01}) {
    const Eigen::Vector3d nl(-std::cos(angle), std::sin(angle), 0), nr(std::cos(angle), 0, std::sin(angle));
    const ContactScores cs = contact_scores({0, 0, 0}, {0.05, 0, 0}, nl, nr, {1, 0, 0});
    EXPECT_NEAR(cs.left, std::cos(angle), 1e-12);
    const Antipodal a = antipodal(cs, mu);
    EXPECT_EQ(a.ok, angle < edge) << angle;
    EXPECT_NEAR(a.mu_required, std::tan(angle), 1e-9);
  }
  // Coincident contacts: the closing direction stands in for the line.
  const ContactScores one = contact_scores({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0});
  EXPECT_DOUBLE_EQ(one.left, 1.0);
  // A normal perpendicular to the line needs infinite friction.
  EXPECT_FALSE(antipodal(contact_scores({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 0, 0}), 10).ok);
}

TEST(Metrics, InlierScoreAndDerivedMaxima) {
  EXPECT_DOUBLE_EQ(inlier_score(27, 135), 0.2);
  EXPECT_DOUBLE_EQ(inlier_score(500, 135), 1.0);  // clipped (6.5 notes it can exceed 1)
  EXPECT_THROW(inlier_score(1, 0), Error);
  const V size(0.05f, 0.08f, 0.015f);
  // 6.5: closing-region volume over the voxel volume: 60 cm^3 / (2.5 mm)^3 = 3840.
  EXPECT_NEAR(max_inliers_volume(size, 0.0025), 3840, 1);
  // Largest section of the box: the 50 x 80 mm face... or the diagonal 80 x hypot(50, 15).
  EXPECT_NEAR(max_inliers_surface(size, 0.0025), std::floor(0.08 * std::hypot(0.05, 0.015) / 6.25e-6), 1);
  EXPECT_THROW(max_inliers_volume(size, 0), Error);
}

TEST(Metrics, WeightsSummingToZeroAreRejected) {
  Weights w;
  EXPECT_NO_THROW(check_weights(w));
  w = {0, 0, 0, 0};
  EXPECT_THROW(check_weights(w), Error);
  w = {1, -1, 1, 1};
  EXPECT_THROW(check_weights(w), Error);
  Scores s;
  s.normal = 1, s.orientation = 0.5, s.contact_left = 0.25, s.contact_right = 0.75, s.inliers = 0.1;
  EXPECT_DOUBLE_EQ(total_score(s, {1, 1, 1, 2}), 1 + 0.5 + 1.0 + 0.2);  // eq. 6.8
}

}  // namespace uwgrasp::grasp
