#pragma once
// Metrics over a detector's ranked grasps, judged against the truth: top-1 success per friction
// coefficient, precision@k and average precision in graspnetAPI's manner (Fang et al. 2020:
// precision@k counts a missing grasp as a failure; AP is the mean of precision@k over k = 1..K,
// then over the friction coefficients), and the mix of outcomes.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "uwgrasp/eval/judge.hpp"

namespace uwgrasp::eval {

struct SummaryConfig {
  std::vector<double> mu = {0.2, 0.3, 0.4, 0.6, 0.8};
  double reference_mu = 0.4;  // the friction coefficient of "success" and precision@k
  std::size_t top = 10;       // K: grasps judged, and the k range of AP
};
// Throws Error naming the value for an empty list, a mu <= 0 or not finite, or top = 0.
void check_summary(const SummaryConfig& cfg);

// What became of a grasp at a given mu: it holds, it closes without force closure, or the
// verdict that stopped it.
enum class Outcome : std::uint8_t {
  holds, not_force_closure, collision, miss, other_object, too_wide, too_narrow
};
inline constexpr int kOutcomes = 7;
Outcome outcome(const Judgement& j, double mu);
const char* outcome_name(Outcome o);

struct Summary {
  std::vector<double> mu;
  std::vector<bool> top1;            // per mu: the best-ranked grasp holds (false: no grasp)
  std::array<double, 3> precision{}; // @1, @5, @10 at the reference mu
  std::vector<double> ap_per_mu;
  double ap = 0.0;
  std::array<std::size_t, kOutcomes> outcomes{};  // of the judged grasps at the reference mu
  std::size_t judged = 0;
};

// Share of the first k grasps that hold at mu; grasps missing below k count as failures.
double precision_at(std::span<const Judgement> ranked, std::size_t k, double mu);

// `ranked`: the judgements of the grasps in rank order (at most cfg.top are used).
Summary summarise(std::span<const Judgement> ranked, const SummaryConfig& cfg);

}  // namespace uwgrasp::eval
