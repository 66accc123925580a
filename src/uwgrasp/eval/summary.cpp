#include "uwgrasp/eval/summary.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::eval {

void check_summary(const SummaryConfig& cfg) {
  if (cfg.mu.empty()) throw Error("mu: the list of friction coefficients is empty");
  for (const double m : cfg.mu)
    if (!(m > 0.0) || !std::isfinite(m))
      throw Error("mu: friction coefficients must be positive, got " + std::to_string(m));
  if (!(cfg.reference_mu > 0.0) || !std::isfinite(cfg.reference_mu))
    throw Error("reference mu must be positive, got " + std::to_string(cfg.reference_mu));
  if (cfg.top == 0) throw Error("top: at least one grasp must be judged");
}

Outcome outcome(const Judgement& j, double mu) {
  switch (j.verdict) {
    case Verdict::closes: return j.holds(mu) ? Outcome::holds : Outcome::not_force_closure;
    case Verdict::collision: return Outcome::collision;
    case Verdict::miss: return Outcome::miss;
    case Verdict::other_object: return Outcome::other_object;
    case Verdict::too_wide: return Outcome::too_wide;
    case Verdict::too_narrow: return Outcome::too_narrow;
  }
  return Outcome::miss;
}

const char* outcome_name(Outcome o) {
  static const char* names[kOutcomes] = {"holds",        "not_force_closure", "collision", "miss",
                                         "other_object", "too_wide",          "too_narrow"};
  return names[static_cast<int>(o)];
}

double precision_at(std::span<const Judgement> ranked, std::size_t k, double mu) {
  if (k == 0) return 0.0;
  std::size_t held = 0;
  for (std::size_t i = 0; i < std::min(k, ranked.size()); ++i) held += ranked[i].holds(mu) ? 1 : 0;
  return double(held) / double(k);
}

Summary summarise(std::span<const Judgement> all, const SummaryConfig& cfg) {
  check_summary(cfg);
  const std::span<const Judgement> ranked = all.first(std::min(all.size(), cfg.top));
  Summary s;
  s.mu = cfg.mu;
  s.judged = ranked.size();
  for (const double mu : cfg.mu) {
    s.top1.push_back(!ranked.empty() && ranked.front().holds(mu));
    double sum = 0.0;
    for (std::size_t k = 1; k <= cfg.top; ++k) sum += precision_at(ranked, k, mu);
    s.ap_per_mu.push_back(sum / double(cfg.top));
  }
  double total = 0.0;
  for (const double a : s.ap_per_mu) total += a;
  s.ap = total / double(s.ap_per_mu.size());
  const std::size_t ks[3] = {1, 5, 10};
  for (int i = 0; i < 3; ++i) s.precision[i] = precision_at(ranked, ks[i], cfg.reference_mu);
  for (const Judgement& j : ranked) ++s.outcomes[static_cast<int>(outcome(j, cfg.reference_mu))];
  return s;
}

}  // namespace uwgrasp::eval
