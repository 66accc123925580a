// Figures 8.13-8.16 of report.md: the best grasp of every iteration drawn on its object, and
// histograms of their scores; and the overview across water conditions.
#include <opencv2/core.hpp>

#include <filesystem>

#include "experiments/experiments_report.hpp"

namespace uwgrasp::experiments {

namespace {
const char* figure_number(const std::string& object) {
  return object == "barbell" ? "8.13" : object == "ring" ? "8.14" : object == "cross" ? "8.15" : "-";
}

std::vector<double> best_scores(const FinalObject& f, double (*get)(const grasp::Scores&)) {
  std::vector<double> v;
  for (const auto& g : f.best) v.push_back(get(g.scores));
  return v;
}

std::string object_figure(const FinalObject& f, const Condition& c, const std::string& dir) {
  const std::string file = c.name + "_fig" + figure_number(f.name) + "_" + f.name + ".png";
  viz::Picture pic;
  pic.title = "Figure " + std::string(figure_number(f.name)) + " (" + c.name + "): best grasp of each iteration, " + f.name;
  pic.legend.push_back(fmt("%zu grasps from %zu iterations, %s sampler, %u candidates each", f.best.size(),
                           f.feasible.size() + f.failures, grasp::sampler_name(f.cfg.grasp.sampler.kind),
                           f.cfg.grasp.sampler.samples));
  pic.legend.push_back("best score " + median_range(best_scores(f, [](const grasp::Scores& s) { return s.total; }),
                                                    "", "%.2f") + ", median (range)");
  // Fingers and palm only, from a fixed 0.9 m: fifty grippers with their bodies hide the object,
  // and a fragment's own extent would zoom in on nothing.
  const auto wires = grasp_wires(f.best, f.frames, f.cfg.grasp.gripper, false);
  viz::View view;
  view.distance = 0.9;
  write_png((std::filesystem::path(dir) / file).string(), viz::draw(f.view, wires, pic, view, f.focus));
  return file;
}

std::string histogram_figure(const ConditionResult& r, const std::string& dir) {
  struct Metric {
    const char* name;
    double lo, hi;
    double (*get)(const grasp::Scores&);
  };
  const Metric metrics[] = {
      {"normal alignment q_n", 0, 1, [](const grasp::Scores& s) { return s.normal; }},
      {"orientation q_o", 0, 1, [](const grasp::Scores& s) { return s.orientation; }},
      {"contacts q_cl + q_cr", 0, 2, [](const grasp::Scores& s) { return s.contact_left + s.contact_right; }},
      {"inliers q_i", 0, 1, [](const grasp::Scores& s) { return s.inliers; }},
      {"total q_tot", 0, 0, [](const grasp::Scores& s) { return s.total; }},
  };
  std::vector<cv::Mat> tiles;
  for (const auto& m : metrics) {
    std::vector<double> all;
    for (const auto& f : r.finals) {
      const auto v = best_scores(f, m.get);
      all.insert(all.end(), v.begin(), v.end());
    }
    tiles.push_back(viz::histogram(all, 20, m.lo, m.hi, std::string("Figure 8.16 (") + r.condition.name + "): " + m.name,
                                   "score of the best grasps, all objects"));
  }
  const std::string file = r.condition.name + "_fig8.16_scores.png";
  write_png((std::filesystem::path(dir) / file).string(), viz::grid(tiles, 3));
  return file;
}
}  // namespace

void write_figures(std::ostringstream& md, const ConditionResult& r, const std::string& dir) {
  md << "### Figures 8.13-8.16: the best grasp of each iteration\n\n"
        "Each iteration detects grasps on every object with its Table 8.5 preset (3000 candidates) "
        "and keeps the best; the figures draw their fingers and palms on the first iteration's "
        "cloud from 0.9 m, coloured by score.\n\n"
        "| object | iterations with a grasp | feasible per detection | best score | width m | detection time | errors |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& f : r.finals) {
    std::vector<double> width;
    for (const auto& g : f.best) width.push_back(g.width);
    std::string errors = std::to_string(f.failures);
    for (const auto& e : f.errors) errors += "; " + e;
    md << "| " << f.name << " | " << f.best.size() << " / " << f.feasible.size() + f.failures << " | "
       << median_range(f.feasible, "", "%.0f") << " | "
       << median_range(best_scores(f, [](const grasp::Scores& s) { return s.total; }), "", "%.3f") << " | "
       << median_range(width, "", "%.4f") << " | " << median_range(f.detect_ms, " ms", "%.0f") << " | " << errors
       << " |\n";
  }
  md << "\n";
  for (const auto& f : r.finals)
    if (!f.view.empty()) md << "![" << f.name << "](" << object_figure(f, r.condition, dir) << ")\n\n";
  md << "![score histograms](" << histogram_figure(r, dir) << ")\n\n";
}

void write_overview(std::ostringstream& md, const std::vector<ConditionResult>& results) {
  md << "## Overview: the water conditions side by side\n\n"
        "*Object coverage*: the detected object's points over the object's visible pixels (truth "
        "labels) - near 1 when segmentation found the whole object, small when it kept a fragment, "
        "and then the grasps are grasps on a fragment.\n\n"
        "| water | object | object coverage | grasp found | feasible of 3000 | best score | "
        "Table 8.3 feasible share (preset sampler) |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& r : results)
    for (const auto& f : r.finals) {
      std::string share = "-";
      for (const auto& row : r.sampling)
        if (row.object == f.name && row.kind == f.cfg.grasp.sampler.kind && !row.feasible.empty())
          share = fmt("%.2f %%", 100 * summarise(row.feasible).mean / row.samples);
      md << "| " << r.condition.name << " | " << f.name << " | " << median_range(f.coverage, "", "%.2f")
         << " | " << f.best.size() << " / "
         << f.feasible.size() + f.failures << " | " << median_range(f.feasible, "", "%.0f") << " | "
         << median_range(best_scores(f, [](const grasp::Scores& s) { return s.total; }), "", "%.3f") << " | "
         << share << " |\n";
    }
  md << "\n";
}

}  // namespace uwgrasp::experiments
