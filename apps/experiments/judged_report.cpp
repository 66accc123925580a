// report.md of the judged study (judged_study.hpp): judged success per scene and water, the
// failure modes of the top-1, the calibration of the detector's scores, and one figure per object.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstring>
#include <map>
#include <set>
#include <numbers>
#include <sstream>

#include "app/common.hpp"
#include "app/simulation.hpp"
#include "experiments/experiments_report.hpp"
#include "experiments/judged_study.hpp"
#include "uwgrasp/io/atomic_file.hpp"
#include "uwgrasp/io/config_schema.hpp"

namespace uwgrasp::experiments {

namespace {
std::size_t mu_index(const JudgedPlan& p) {
  const auto& mu = p.summary.mu;
  const auto it = std::find(mu.begin(), mu.end(), p.summary.reference_mu);
  return it == mu.end() ? mu.size() : std::size_t(it - mu.begin());
}

// Means over the runs of a set of cases.
struct Totals {
  std::size_t runs = 0, no_grasp = 0, errors = 0;
  std::vector<double> top1;  // per mu: share of runs whose top-1 holds
  double robust = 0, p1 = 0, p10 = 0, ap = 0;
  std::size_t robust_n = 0;
  double share = 0;                // mean feasible share of the candidates drawn
  std::size_t share_n = 0;
  std::vector<double> detect_ms;   // runs where detection ran
  std::map<std::string, std::size_t> modes;  // top-1 outcome (with collision detail)
};

std::string top1_mode(const JudgedRun& r, double mu, bool exists) {
  if (!exists && !r.has_top1) return "no grasp, and none exists (right)";
  if (!r.error.empty()) return "no grasp (detection stopped)";
  if (!r.has_top1) return "no grasp (none feasible)";
  const eval::Judgement& j = r.top1;
  if (j.verdict != eval::Verdict::collision) return eval::outcome_name(eval::outcome(j, mu));
  const std::string part = grasp::part_name(grasp::Part(j.part));
  if (j.object == sim::kSeafloorObject) return "collision: " + part + " in the seafloor";
  return "collision: " + part + (j.inside ? " wholly inside the object" : j.visible ? " through a seen surface" : " through an unseen surface");
}

Totals totals(const std::vector<const JudgedCaseResult*>& cases, const JudgedPlan& plan) {
  Totals t;
  t.top1.assign(plan.summary.mu.size(), 0.0);
  for (const auto* c : cases)
    for (const JudgedRun& r : c->runs) {
      ++t.runs;
      t.errors += r.error.empty() ? 0 : 1;
      t.no_grasp += r.has_top1 ? 0 : 1;
      ++t.modes[top1_mode(r, plan.summary.reference_mu, c->grasp_exists)];
      if (r.error.empty() && r.candidates > 0) {
        t.share += double(r.feasible) / double(r.candidates), ++t.share_n;
        t.detect_ms.push_back(r.detect_ms);
      }
      if (!r.has_top1 && !c->grasp_exists) {  // "no grasp" is right: a success on every count
        for (double& v : t.top1) v += 1;
        t.p1 += 1, t.p10 += 1, t.ap += 1, t.robust += 1, ++t.robust_n;
        continue;
      }
      for (std::size_t m = 0; m < t.top1.size(); ++m) t.top1[m] += r.summary.top1[m] ? 1 : 0;
      t.p1 += r.summary.precision[0], t.p10 += r.summary.precision[2], t.ap += r.summary.ap;
      if (std::isfinite(r.robust)) t.robust += r.robust, ++t.robust_n;
    }
  const double n = double(std::max<std::size_t>(t.runs, 1));
  for (double& v : t.top1) v /= n;
  t.p1 /= n, t.p10 /= n, t.ap /= n;
  // A run without a grasp has no robust share: it counts as 0, like a failed grasp.
  t.robust /= n;
  t.share /= double(std::max<std::size_t>(t.share_n, 1));
  return t;
}

std::string pct(double v) { return fmt("%.0f %%", 100.0 * v); }

void success_row(std::ostringstream& md, const std::string& what, const Totals& t, const JudgedPlan& p) {
  const std::size_t k = mu_index(p);
  md << "| " << what << " | " << t.runs << " | " << (k < t.top1.size() ? pct(t.top1[k]) : "-") << " | ";
  for (std::size_t m = 0; m < t.top1.size(); ++m) md << (m ? " / " : "") << fmt("%.0f", 100 * t.top1[m]);
  md << " | " << pct(t.robust) << " | " << pct(t.p10) << " | " << fmt("%.3f", t.ap) << " | " << t.no_grasp
     << " | " << (t.share_n ? pct(t.share) : "-") << " | "
     << (t.detect_ms.empty() ? "-" : fmt("%.0f", summarise(t.detect_ms).median)) << " |\n";
}

void success_header(std::ostringstream& md, const JudgedPlan& p, const char* first) {
  md << "| " << first << " | runs | top-1 success at mu " << io::shortest(p.summary.reference_mu)
     << " | top-1 at mu ";
  for (std::size_t m = 0; m < p.summary.mu.size(); ++m) md << (m ? "/" : "") << io::shortest(p.summary.mu[m]);
  md << " (%) | robust top-1 | precision@10 | AP | no grasp | feasible share | detect ms |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
}

void write_success(std::ostringstream& md, const std::vector<JudgedCaseResult>& results, const JudgedPlan& p) {
  std::vector<std::string> waters;
  for (const auto& r : results)
    if (std::find(waters.begin(), waters.end(), r.c.label()) == waters.end()) waters.push_back(r.c.label());
  md << "## Judged success\n\nTop-1 success: the share of iterations whose best-ranked grasp holds "
        "(no collision, closes on the object, force closure at mu); an iteration without a grasp is a "
        "failure, unless a search over the object's true surface finds no grasp of the gripper that "
        "holds it either (eval/exists.hpp), where it is the right answer and counts as a success on "
        "every measure (scenes marked *). Robust: the share of " << p.robust.samples << " perturbed poses (sigma "
     << fmt("%.0f mm, %.0f deg", p.robust.sigma_position * 1000, p.robust.sigma_angle * 180 / std::numbers::pi)
     << ") of the top-1 that still hold at mu " << io::shortest(p.robust.mu)
     << ", averaged over iterations (0 without a grasp). Precision@10 and AP over the top "
     << p.summary.top << " as graspnetAPI counts them (missing grasps fail). Feasible share: the "
        "candidates that passed every check before ranking, of those drawn (mean over the runs); "
        "detect ms: the median whole detection (preprocessing to ranking) per run. Every run, with "
        "the detector's own prediction for its top-1 beside the judge's finding: runs.csv.\n\n";
  success_header(md, p, "water");
  for (const auto& w : waters) {
    std::vector<const JudgedCaseResult*> cs;
    for (const auto& r : results)
      if (r.c.label() == w) cs.push_back(&r);
    success_row(md, w, totals(cs, p), p);
  }
  md << "\n";
  success_header(md, p, "scene, water");
  for (const auto& r : results)
    success_row(md, r.c.scene + (r.grasp_exists ? "" : " *") + ", " + r.c.label(), totals({&r}, p), p);
  md << "\n";
}

void write_modes(std::ostringstream& md, const std::vector<JudgedCaseResult>& results, const JudgedPlan& p) {
  std::vector<const JudgedCaseResult*> all;
  for (const auto& r : results) all.push_back(&r);
  const Totals t = totals(all, p);
  md << "## What became of the top-1\n\nOver all " << t.runs << " iterations, at mu "
     << io::shortest(p.summary.reference_mu) << ". A collision through an unseen surface puts a part in "
     << "the object's back, which the camera could not see.\n\n| outcome | iterations | share |\n|---|---|---|\n";
  std::vector<std::pair<std::string, std::size_t>> modes(t.modes.begin(), t.modes.end());
  std::stable_sort(modes.begin(), modes.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  for (const auto& [m, n] : modes) md << "| " << m << " | " << n << " | " << pct(double(n) / double(t.runs)) << " |\n";
  md << "\n";
}
// One line per iteration: what the detector predicted for its top-1 beside what the judge found,
// so a failing case can be taken apart without rerunning it.
std::string runs_csv(const std::vector<JudgedCaseResult>& results, const JudgedPlan& p) {
  std::ostringstream csv;
  csv << "scene,water,seed,outcome,judged_mu_min,judged_width_m,robust_top1,precision_at_10,"
         "predicted_mu,predicted_robustness,predicted_width_m,contact_seen_left,contact_seen_right,"
         "feasible,candidates,object_points,visible_points,detect_ms,stereo_depth_error,stereo_completeness,error\n";
  const auto num = [](double v) { return std::isfinite(v) ? fmt("%.4f", v) : std::string(); };
  for (const auto& r : results)
    for (std::size_t i = 0; i < r.runs.size(); ++i) {
      const JudgedRun& run = r.runs[i];
      std::string error = run.error;
      std::replace(error.begin(), error.end(), ',', ';');
      std::replace(error.begin(), error.end(), '\n', ' ');
      std::string outcome = top1_mode(run, p.summary.reference_mu, r.grasp_exists);
      std::replace(outcome.begin(), outcome.end(), ',', ';');  // "no grasp, and none exists"
      const bool closes = run.has_top1 && run.top1.verdict != eval::Verdict::collision &&
                          run.top1.verdict != eval::Verdict::miss;
      csv << r.c.scene << "," << r.c.label() << "," << p.base.seed + i << ","
          << outcome << ","
          << (run.has_top1 ? num(run.top1.mu_min) : "") << "," << (closes ? num(run.top1.width) : "") << ","
          << num(run.robust) << "," << num(run.summary.precision[2]) << "," << num(run.predicted_mu) << ","
          << num(run.predicted_robustness) << "," << num(run.predicted_width) << ","
          << (run.has_top1 ? std::to_string(int(run.contact_seen[0])) : "") << ","
          << (run.has_top1 ? std::to_string(int(run.contact_seen[1])) : "") << "," << run.feasible << ","
          << run.candidates << "," << run.object_points << "," << run.visible_points << ","
          << fmt("%.1f", run.detect_ms) << "," << num(run.depth_error) << "," << num(run.completeness) << ","
          << error << "\n";
    }
  return csv.str();
}
}  // namespace

void write_judged_calibration(std::ostringstream& md, const std::vector<JudgedCaseResult>& results,
                              const JudgedPlan& p);

namespace {
// Stereo cases: how well the matched cloud covers and places the object, beside the grasps.
void write_stereo(std::ostringstream& md, const std::vector<JudgedCaseResult>& results) {
  if (std::none_of(results.begin(), results.end(), [](const auto& r) { return r.c.sensor == "stereo"; })) return;
  md << "## Stereo\n\nThe stereo cases render the rig's pair (0.12 m baseline) and match it with the "
        "configured matcher (stereo.*) into the organised cloud the detector takes. Per case, medians over "
        "the iterations: the object's depth error (median of |z - z_true| / z_true over its visible "
        "pixels) and completeness (the share of those pixels with a depth); the grasp results are in the "
        "tables above, the RGB-D rows beside them.\n\n| scene, water | depth error | completeness |\n"
        "|---|---|---|\n";
  for (const auto& r : results) {
    if (r.c.sensor != "stereo") continue;
    std::vector<double> e, c;
    for (const auto& run : r.runs)
      if (std::isfinite(run.depth_error)) e.push_back(run.depth_error), c.push_back(run.completeness);
    const auto med = [](std::vector<double> v) {
      if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
      std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    md << "| " << r.c.scene << ", " << r.c.label() << " | " << fmt("%.2f %%", 100 * med(e)) << " | "
       << fmt("%.1f %%", 100 * med(c)) << " |\n";
  }
  md << "\n";
}
// One figure per object: a row per pose, its waters side by side.
void write_figures(std::ostringstream& md, const std::vector<JudgedCaseResult>& results,
                   const std::string& dir) {
  md << "## Figures\n\nThe first iteration of each case: the true scene, the top grasps coloured "
        "by their judged outcome (green holds, amber closes without force closure, red collides); "
        "a row per scene, a column per water.\n\n";
  std::map<std::string, std::vector<cv::Mat>> tiles;
  std::map<std::string, std::set<std::string>> waters;
  std::vector<std::string> order;
  for (const auto& r : results) {
    if (r.tile.empty()) continue;
    // A scene file is named by its stem: its path would make a path of the figure's name.
    std::string object = std::filesystem::path(r.c.scene).stem().string();
    for (const char* pose : {"_lying", "_turned"})
      if (object.ends_with(pose)) object.resize(object.size() - std::strlen(pose));
    if (!tiles.count(object)) order.push_back(object);
    tiles[object].push_back(r.tile);
    waters[object].insert(r.c.label());
  }
  for (const auto& object : order) {
    const std::string file = "judged_" + object + ".png";
    write_png((std::filesystem::path(dir) / file).string(),
              viz::grid(tiles[object], int(waters[object].size())));
    md << "![" << object << "](" << file << ")\n\n";
  }
}
}  // namespace

void write_judged_report(const std::string& dir, const std::vector<JudgedCaseResult>& results,
                         const JudgedPlan& plan, const std::string& command, const std::string& title) {
  make_output_dir(dir);
  std::ostringstream md;
  md << "# " << title << "\n\nEvery iteration renders the scene with the next seed, runs the detector with "
     << (plan.sets.empty() ? "the default settings" : "the settings below")
     << " (the object of interest selected as a user would: by its colour) and judges its ranked grasps "
        "against the objects' full meshes with `uwgrasp evaluate`'s judge (eval/): collision of fingers, "
        "palm and body with the objects and the seafloor, the pads' closing, force closure on the line of "
        "action, robustness under pose noise.\n\nMade by:\n\n```\n"
     << command << "\n```\n\n| | |\n|---|---|\n| uwgrasp | " << UWGRASP_VERSION << " |\n| seed | "
     << plan.base.seed << " (iteration i uses seed + i) |\n| iterations | " << plan.iterations
     << " per scene and water |\n";
  if (plan.withhold_attitude)
    md << "| attitude | withheld: the detector is given no attitude and the camera's mount as "
          "looking straight ahead (the scenes' cameras are pitched down), as for a cloud file |\n";
  if (plan.slope != 0.0)
    md << "| seafloor | " << fmt("rising %.1f", plan.slope * 180.0 / std::numbers::pi)
       << " deg ahead: the detector is given the vehicle's attitude against gravity |\n";
  if (!plan.sets.empty()) {
    md << "| settings |";
    for (const auto& s : plan.sets) md << " `" << s << "`";
    md << " |\n";
  }
  double seconds = 0;
  for (const auto& r : results) seconds += r.seconds;
  md << "| time | " << fmt("%.0f", seconds) << " s |\n\n";
  write_success(md, results, plan);
  write_stereo(md, results);
  write_modes(md, results, plan);
  if (plan.calibrate) write_judged_calibration(md, results, plan);
  write_figures(md, results, dir);
  io::write_text((std::filesystem::path(dir) / "runs.csv").string(), runs_csv(results, plan));
  io::write_text((std::filesystem::path(dir) / "report.md").string(), md.str());
}

}  // namespace uwgrasp::experiments
