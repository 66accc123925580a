// The judged table of report.md: each condition's top grasps judged against the true shapes,
// beside the thesis's judgement by inspection (8.5).
#include <map>

#include "experiments/experiments_report.hpp"
#include "uwgrasp/grasp/samplers.hpp"

namespace uwgrasp::experiments {

namespace {
void judged_row(std::ostringstream& md, const std::string& object, const std::string& how,
                const std::vector<Judged>& runs) {
  const eval::SummaryConfig sc;
  std::vector<double> top1(sc.mu.size(), 0.0);
  double p10 = 0, ap = 0;
  std::map<std::string, std::size_t> mix;
  for (const Judged& j : runs) {
    for (std::size_t m = 0; m < top1.size(); ++m) top1[m] += j.summary.top1[m] ? 1 : 0;
    p10 += j.summary.precision[2], ap += j.summary.ap;
    ++mix[j.top1];
  }
  const double n = double(std::max<std::size_t>(runs.size(), 1));
  md << "| " << object << " | " << how << " | "
     << (how.starts_with("preset") ? "suitable (all 50)" : "-") << " | " << runs.size() << " | "
     << fmt("%.0f %%", 100 * top1[2] / n) << " | ";
  for (std::size_t m = 0; m < top1.size(); ++m) md << (m ? " / " : "") << fmt("%.0f", 100 * top1[m] / n);
  md << " | " << fmt("%.0f %%", 100 * p10 / n) << " | " << fmt("%.3f", ap / n) << " | ";
  bool first = true;
  for (const auto& [k, v] : mix) md << (first ? "" : ", ") << k << " " << v, first = false;
  md << " |\n";
}
}  // namespace

void write_judged(std::ostringstream& md, const ConditionResult& r) {
  md << "### Judged against the truth (not in the thesis)\n\n"
        "The thesis judged its 50 best grasps per object by inspection and found them suitable (8.5). "
        "Here every iteration's top 10 is judged against the objects' full shapes with `uwgrasp "
        "evaluate`'s judge (collision of fingers, palm and body with every object and the seafloor, the "
        "closing of the pads, force closure at mu 0.4 on the line of action): the Table 8.5 preset's "
        "detection, and each sampler's 5000 candidates of Table 8.3 with the preset otherwise. Top-1 "
        "success is the share of iterations whose best grasp holds; an iteration without a grasp fails.\n\n"
        "| object | grasps from | thesis (by inspection) | iterations | top-1 success at mu 0.4 | "
        "top-1 at mu 0.2/0.3/0.4/0.6/0.8 (%) | precision@10 | AP | top-1 outcomes |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  for (const FinalObject& f : r.finals) {
    judged_row(md, f.name, std::string("preset, ") + grasp::sampler_name(f.cfg.grasp.sampler.kind), f.judged);
    for (const SamplerRow& row : r.sampling)
      if (row.object == f.name)
        judged_row(md, f.name, fmt("%s, %u candidates", grasp::sampler_name(row.kind), row.samples), row.judged);
  }
  md << "\n";
}

}  // namespace uwgrasp::experiments
