// report.md for uwgrasp experiments: every table beside the thesis's numbers (chapter 8), with
// the figures as PNGs next to it.
#include <algorithm>
#include <cstdarg>
#include <filesystem>
#include <numeric>
#include <sstream>
#include <thread>

#include "app/common.hpp"
#include "experiments/experiments.hpp"
#include "experiments/experiments_report.hpp"
#include "uwgrasp/io/atomic_file.hpp"

namespace uwgrasp::experiments {

std::string fmt(const char* format, ...) {
  va_list args, again;
  va_start(args, format);
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  std::string out(static_cast<std::size_t>(std::max(n, 0)), '\0');
  std::vsnprintf(out.data(), out.size() + 1, format, again);
  va_end(again);
  return out;
}

Summary summarise(std::vector<double> v) {
  Summary s;
  s.n = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.min = v.front();
  s.max = v.back();
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
  const std::size_t h = v.size() / 2;
  s.median = v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
  return s;
}

std::string median_range(const std::vector<double>& v, const char* unit, const char* format) {
  if (v.empty()) return "-";
  const Summary s = summarise(v);
  return fmt(format, s.median) + unit + " (" + fmt(format, s.min) + "-" + fmt(format, s.max) + ")";
}

namespace {
const char* kIntro =
    "Thesis chapter 8 repeated on uwgrasp's embedded simulator. Each iteration renders the scene "
    "again with the next seed (new sensor noise and marine snow when the condition has them); the "
    "vehicle is stationary, as in the thesis. Times are wall-clock on the machine below, as "
    "median (min-max) over the iterations; the thesis's are averages on its own machine with ROS, "
    "Gazebo and PCL, so compare orders of magnitude, not digits.\n\n"
    "- **clear**: Jerlov-I-like water and a perfect sensor - the thesis's conditions (7.4.1).\n"
    "- **coastal**, **turbid**: the water presets of `sim/water.hpp` with depth noise, dropouts and "
    "marine snow on - conditions the thesis assumed away.\n";

void write_header(std::ostringstream& md, const ExperimentPlan& plan, const std::string& command,
                  const std::vector<ConditionResult>& results) {
  md << "# uwgrasp experiments: thesis chapter 8 on simulated scenes\n\n" << kIntro << "\n";
  md << "Made by:\n\n```\n" << command << "\n```\n\n";
  md << "| | |\n|---|---|\n";
  md << "| uwgrasp | " << UWGRASP_VERSION << " |\n";
  md << "| seed | " << plan.base.seed << " (iteration i uses seed + i) |\n";
  md << "| iterations | " << plan.iterations << " (tables 8.3, 8.5, figures 8.13-8.16); "
     << plan.short_iterations << " (tables 8.1, 8.2, 8.4, as the thesis); the all-points check of 8.4: "
     << plan.brute_iterations << " |\n";
  md << "| threads | " << (plan.base.threads ? std::to_string(plan.base.threads) : "all") << " of "
     << std::thread::hardware_concurrency() << " cores |\n";
  md << "| camera | " << plan.base.sim.camera.width << "x" << plan.base.sim.camera.height << ", hfov "
     << fmt("%.3f", plan.base.sim.camera.hfov) << " rad |\n";
  for (const auto& r : results) md << "| " << r.condition.name << " | " << fmt("%.0f", r.seconds) << " s |\n";
  md << "\n";
}
}  // namespace

void write_report(const std::string& dir, const std::vector<ConditionResult>& results,
                  const ExperimentPlan& plan, const std::string& command) {
  make_output_dir(dir);
  std::ostringstream md;
  write_header(md, plan, command, results);
  write_overview(md, results);
  write_vehicle_model(md, plan.base, dir);
  for (const auto& r : results) {
    const Condition& c = r.condition;
    md << "## " << c.name << ": " << c.water << " water, " << (c.noise ? "realistic sensor" : "perfect sensor")
       << (c.sets.empty() ? ", the thesis's settings" : ", adapted settings") << "\n\n";
    if (!c.sets.empty()) {
      md << "On top of every preset:";
      for (const auto& s : c.sets) md << " `" << s << "`";
      md << "\n\n";
    }
    write_segmentation(md, r);
    write_sampling(md, r);
    write_checking(md, r);
    write_weights(md, r);
    write_judged(md, r);
    write_figures(md, r, dir);
    write_vehicle_runs(md, r);
  }
  io::write_text((std::filesystem::path(dir) / "report.md").string(), md.str());
}

}  // namespace uwgrasp::experiments
