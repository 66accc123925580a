#pragma once
// How well one of the detector's own scores predicts the judged outcome, over many grasps: the
// Spearman rank correlation between score and success (ties get their mean rank), the area
// under the ROC curve (the chance that a random success outscores a random failure), and the
// success rate of the top decile by score beside the base rate. Tells which scores lie.
#include <cstddef>
#include <span>

namespace uwgrasp::eval {

struct Calibration {
  std::size_t n = 0;
  double base_rate = 0.0;   // share of successes
  double spearman = 0.0;    // in [-1, 1]; 0 when either side is constant
  double auc = 0.5;         // 0.5 when there are no successes or no failures
  double top_decile = 0.0;  // success rate of the highest-scored tenth (at least one grasp)
};

// Higher score = predicted better (pass -x for a quantity where lower is better). Throws Error
// when the spans differ in length; non-finite scores rank lowest.
Calibration calibrate(std::span<const double> score, std::span<const bool> success);

// Spearman's rank correlation of two samples (ties share their mean rank); 0 when either is
// constant. Throws Error when the spans differ in length.
double spearman(std::span<const double> a, std::span<const double> b);

}  // namespace uwgrasp::eval
