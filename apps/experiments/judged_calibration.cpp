// The calibration section of the judged study's report: how well each of the detector's own
// scores, and its friction estimate mu_required, predicts the judged outcome.
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "experiments/experiments_report.hpp"
#include "experiments/judged_study.hpp"
#include "uwgrasp/io/config_schema.hpp"

namespace uwgrasp::experiments {

namespace {
struct Metric {
  const char* name;
  double (*get)(const ScoredOutcome&);
};
const Metric kMetrics[] = {
    {"q_tot (the ranking)", [](const ScoredOutcome& s) { return s.scores.total; }},
    {"q_n normal alignment", [](const ScoredOutcome& s) { return s.scores.normal; }},
    {"q_o orientation", [](const ScoredOutcome& s) { return s.scores.orientation; }},
    {"q_cl + q_cr contacts", [](const ScoredOutcome& s) { return s.scores.contact_left + s.scores.contact_right; }},
    {"min(q_cl, q_cr)", [](const ScoredOutcome& s) { return std::min(s.scores.contact_left, s.scores.contact_right); }},
    {"q_i inliers", [](const ScoredOutcome& s) { return s.scores.inliers; }},
    {"q_v vehicle", [](const ScoredOutcome& s) { return s.scores.vehicle; }},
    {"-mu_required (own antipodal estimate)", [](const ScoredOutcome& s) { return -s.mu_required; }},
    {"robustness on the model (robust mode)", [](const ScoredOutcome& s) { return s.robustness; }},
    {"q_fc predicted force closure (robust mode)", [](const ScoredOutcome& s) { return s.force_closure; }},
};

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}
}  // namespace

void write_judged_calibration(std::ostringstream& md, const std::vector<JudgedCaseResult>& results,
                              const JudgedPlan& p) {
  std::vector<ScoredOutcome> all;
  for (const auto& r : results) all.insert(all.end(), r.scored.begin(), r.scored.end());
  const auto success = std::make_unique<bool[]>(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) success[i] = all[i].holds;
  const std::span<const bool> y(success.get(), all.size());
  md << "## Calibration of the detector's own scores\n\nEvery feasible candidate of every iteration ("
     << all.size() << "), scored by the detector and judged at mu " << io::shortest(p.summary.reference_mu)
     << ". Spearman: rank correlation of the score with success; AUC: the chance that a grasp that "
        "holds outscores one that does not (0.5 is a coin); top decile: the success rate of the tenth "
        "with the highest score, beside the base rate. A score that predicts nothing cannot rank.\n\n"
        "| score | Spearman | AUC | top decile | base rate |\n|---|---|---|---|---|\n";
  for (const Metric& m : kMetrics) {
    std::vector<double> s(all.size());
    for (std::size_t i = 0; i < all.size(); ++i) s[i] = m.get(all[i]);
    const eval::Calibration c = eval::calibrate(s, y);
    md << "| " << m.name << " | " << fmt("%.3f", c.spearman) << " | " << fmt("%.3f", c.auc) << " | "
       << fmt("%.1f %%", 100 * c.top_decile) << " | " << fmt("%.1f %%", 100 * c.base_rate) << " |\n";
  }
  std::vector<double> ours, judge;
  for (const auto& s : all)
    if (std::isfinite(s.mu_required) && std::isfinite(s.mu_min)) ours.push_back(s.mu_required), judge.push_back(s.mu_min);
  md << "\nThe detector's `mu_required` (robust mode: predicted on the object's model; thesis mode: from "
        "the one-sided cloud's normals) against the judge's "
        "smallest friction coefficient on the full mesh, over the "
     << ours.size() << " candidates that close on the object: median " << fmt("%.2f", median(ours))
     << " against " << fmt("%.2f", median(judge)) << ", rank correlation "
     << fmt("%.3f", eval::spearman(ours, judge)) << ".\n\n";
}

}  // namespace uwgrasp::experiments
