// Summary metrics (graspnetAPI's precision@k and AP) and score calibration on hand-made
// outcomes with known values.
#include <gtest/gtest.h>

#include <cmath>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/eval/calibration.hpp"
#include "uwgrasp/eval/summary.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::eval;

Judgement closes(double mu_min) {
  Judgement j;
  j.verdict = Verdict::closes;
  j.mu_min = mu_min;
  return j;
}
Judgement failed(Verdict v) {
  Judgement j;
  j.verdict = v;
  return j;
}

TEST(Summary, PrecisionCountsMissingGraspsAsFailures) {
  const std::vector<Judgement> r = {closes(0.1), failed(Verdict::collision), closes(0.5)};
  EXPECT_DOUBLE_EQ(precision_at(r, 1, 0.4), 1.0);
  EXPECT_DOUBLE_EQ(precision_at(r, 2, 0.4), 0.5);
  EXPECT_DOUBLE_EQ(precision_at(r, 3, 0.4), 1.0 / 3);
  EXPECT_DOUBLE_EQ(precision_at(r, 3, 0.6), 2.0 / 3);
  EXPECT_DOUBLE_EQ(precision_at(r, 5, 0.6), 2.0 / 5);
}

TEST(Summary, ApIsTheMeanPrecisionOverKThenMu) {
  const std::vector<Judgement> r = {closes(0.1), failed(Verdict::miss), closes(0.5)};
  SummaryConfig cfg;
  cfg.mu = {0.4, 0.6};
  cfg.top = 4;
  const Summary s = summarise(r, cfg);
  // mu 0.4: P@1..4 = 1, 1/2, 1/3, 1/4; mu 0.6: 1, 1/2, 2/3, 2/4.
  EXPECT_NEAR(s.ap_per_mu[0], (1 + 0.5 + 1.0 / 3 + 0.25) / 4, 1e-12);
  EXPECT_NEAR(s.ap_per_mu[1], (1 + 0.5 + 2.0 / 3 + 0.5) / 4, 1e-12);
  EXPECT_NEAR(s.ap, (s.ap_per_mu[0] + s.ap_per_mu[1]) / 2, 1e-12);
  EXPECT_TRUE(s.top1[0] && s.top1[1]);
  EXPECT_EQ(s.outcomes[int(Outcome::holds)], 1u);
  EXPECT_EQ(s.outcomes[int(Outcome::not_force_closure)], 1u);
  EXPECT_EQ(s.outcomes[int(Outcome::miss)], 1u);
  EXPECT_EQ(s.judged, 3u);
}

TEST(Summary, NoGraspIsAFailureEverywhere) {
  const Summary s = summarise({}, {});
  for (bool t : s.top1) EXPECT_FALSE(t);
  EXPECT_EQ(s.ap, 0.0);
  EXPECT_EQ(s.precision[0], 0.0);
}

TEST(Summary, TopLimitsTheJudgedGrasps) {
  std::vector<Judgement> r(20, closes(0.1));
  SummaryConfig cfg;
  cfg.top = 5;
  EXPECT_EQ(summarise(r, cfg).judged, 5u);
}

TEST(Summary, BadConfigIsAnError) {
  SummaryConfig cfg;
  cfg.mu = {0.4, 0.0};
  EXPECT_THROW(summarise({}, cfg), Error);
  cfg.mu = {};
  EXPECT_THROW(check_summary(cfg), Error);
  cfg.mu = {0.4};
  cfg.top = 0;
  EXPECT_THROW(check_summary(cfg), Error);
}

TEST(Calibration, PerfectReversedAndUninformativeScores) {
  const std::vector<double> s = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  const bool y[] = {false, false, false, false, false, true, true, true, true, true};
  const Calibration good = calibrate(s, y);
  EXPECT_DOUBLE_EQ(good.auc, 1.0);
  EXPECT_DOUBLE_EQ(good.base_rate, 0.5);
  EXPECT_DOUBLE_EQ(good.top_decile, 1.0);
  // Spearman of a rank against a 5/5 split: the point-biserial correlation of ranks.
  EXPECT_NEAR(good.spearman, 0.8703882797784892, 1e-12);
  std::vector<double> neg(s.rbegin(), s.rend());
  const Calibration bad = calibrate(neg, y);
  EXPECT_DOUBLE_EQ(bad.auc, 0.0);
  EXPECT_NEAR(bad.spearman, -good.spearman, 1e-12);
  const std::vector<double> flat(10, 1.0);
  const Calibration none = calibrate(flat, y);
  EXPECT_DOUBLE_EQ(none.auc, 0.5);
  EXPECT_DOUBLE_EQ(none.spearman, 0.0);
  EXPECT_THROW(calibrate(flat, std::span<const bool>(y, 3)), Error);
}

TEST(Calibration, TiesShareTheirRankInTheAuc) {
  // Scores 1, 1, 2, 2 with outcomes no, yes, no, yes: each success beats half the failures on
  // average: AUC 0.5... success(1) vs fail(1) tie 0.5, vs fail(2) 0; success(2) vs fail(1) 1,
  // vs fail(2) 0.5 -> (0.5 + 0 + 1 + 0.5) / 4 = 0.5.
  const std::vector<double> s = {1, 1, 2, 2};
  const bool y[] = {false, true, false, true};
  EXPECT_DOUBLE_EQ(calibrate(s, y).auc, 0.5);
  const bool z[] = {false, false, true, true};
  EXPECT_DOUBLE_EQ(calibrate(s, z).auc, 1.0);
}

}  // namespace
