// uwgrasp experiments [--iterations N] --out DIR: the thesis's chapter 8 on the simulated scenes
// in clear water with a perfect sensor (the thesis's conditions), then in coastal and turbid
// water with a realistic sensor; writes DIR/report.md and its figures. With --study judged: the
// detector's grasps on scenes it was not tuned on, judged against the full meshes.
#include <iostream>
#include <numbers>

#include "app/common.hpp"
#include "commands.hpp"
#include "experiments/experiments.hpp"
#include "experiments/judged_study.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/scene_yaml.hpp"

namespace uwgrasp::app {

namespace {
struct ExperimentOptions {
  CommonOptions common;
  std::string out;
  int iterations = 50;
  std::vector<std::string> waters = {"clear", "coastal", "turbid"};
  std::string command;  // as typed, for the report
  std::string study = "thesis";
  std::vector<std::string> scenes = {"held-in"};
  std::vector<std::string> sensors = {"rgbd"};
  std::int64_t robust = 25;
  bool no_calibration = false;
  bool withhold_attitude = false;
  double slope_deg = 0.0;
};

// --scenes: held-in (the real objects' meshes), thesis (its objects alone), or names.
std::vector<std::string> judged_scenes(const std::vector<std::string>& asked) {
  std::vector<std::string> out;
  for (const auto& a : asked) {
    const auto add = [&](const std::vector<std::string>& v) { out.insert(out.end(), v.begin(), v.end()); };
    if (a == "held-in") add(experiments::held_in_scenes());
    else if (a == "thesis") add(experiments::thesis_object_scenes());
    else out.push_back(a);
  }
  return out;
}

int run_judged(const ExperimentOptions& o) {
  const Session session = open_session(o.common);
  experiments::JudgedPlan plan;
  plan.base = session.config;
  plan.sets = o.common.sets;
  plan.iterations = o.iterations;
  plan.robust.samples = std::uint32_t(o.robust);
  plan.calibrate = !o.no_calibration;
  plan.withhold_attitude = o.withhold_attitude;
  plan.slope = o.slope_deg * std::numbers::pi / 180.0;
  const std::vector<std::string> scenes = judged_scenes(o.scenes);
  for (const auto& scene : scenes) (void)io::load_scene(scene);  // bad names fail before any work
  for (const auto& scene : scenes)
    for (const auto& w : o.waters)
      for (const auto& sensor : o.sensors) {
        // "scene": each scene file's own water (else sim.water), with the realistic sensor.
        const bool noisy = w != "clear";
        const std::string preset = w == "clear-noisy" ? "clear" : w == "scene" ? "" : w;
        plan.cases.push_back({scene, preset, noisy, sensor});
      }
  const auto results = experiments::run_judged_study(plan);
  experiments::write_judged_report(o.out, results, plan, o.command,
                                   "uwgrasp judged study: grasps against the full shapes");
  std::cout << "wrote " << o.out << "/report.md and its figures (" << results.size() << " cases, seed "
            << plan.base.seed << ")\n";
  return 0;
}

int run_experiments(const ExperimentOptions& o) {
  if (o.study == "judged") return run_judged(o);
  for (const auto& w : o.waters)
    if (w == "clear-noisy" || w == "scene")
      throw Error("--water " + w + ": only the judged study has it (--study judged)");
  if (o.withhold_attitude || o.slope_deg != 0.0)
    throw Error(std::string(o.withhold_attitude ? "--withhold-attitude" : "--slope") +
                ": only the judged study has it (--study judged)");
  const Session session = open_session(o.common);
  experiments::ExperimentPlan plan;
  plan.base = session.config;
  plan.sets = o.common.sets;
  plan.iterations = o.iterations;
  plan.short_iterations = std::min(o.iterations, 10);
  plan.brute_iterations = std::min(o.iterations, 3);
  const auto results = experiments::run_thesis_study(plan, o.waters);
  experiments::write_report(o.out, results, plan, o.command);
  std::cout << "wrote " << o.out << "/report.md and its figures (";
  for (const auto& r : results) std::cout << r.condition.name << " " << static_cast<int>(r.seconds) << " s; ";
  std::cout << "seed " << plan.base.seed << ")\n";
  return 0;
}

std::string command_line(int argc, char** argv) {
  std::string s = "uwgrasp";
  for (int i = 1; i < argc; ++i) s += std::string(" ") + argv[i];
  return s;
}
}  // namespace

void add_experiments_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners,
                             int argc, char** argv) {
  auto* cmd = app.add_subcommand("experiments", "Reproduce the thesis's chapter 8 on simulated scenes");
  auto o = std::make_shared<ExperimentOptions>();
  o->command = command_line(argc, argv);
  cmd->add_option("--out", o->out, "Output directory for report.md and its PNGs")->required();
  cmd->add_option("--iterations", o->iterations, "Iterations per study (the thesis: 50)")
      ->check(CLI::Range(1, 100000))->capture_default_str();
  cmd->add_option("--water", o->waters,
                  "Water conditions to study: clear (perfect sensor), clear-noisy (judged study), coastal, turbid, "
                  "scene (judged study: each scene file's own water)")
      ->check(CLI::IsMember({"clear", "clear-noisy", "coastal", "turbid", "scene"}))->capture_default_str();
  cmd->add_option("--study", o->study, "thesis: chapter 8's tables and figures; judged: grasps judged "
                  "against the full shapes")->check(CLI::IsMember({"thesis", "judged"}))->capture_default_str();
  cmd->add_option("--scenes", o->scenes, "Judged study: held-in (real objects' meshes, every pose), thesis "
                  "(its objects alone) or scene names")->delimiter(',')->capture_default_str();
  cmd->add_option("--robust", o->robust, "Judged study: perturbed poses per top-1 (0: off)")
      ->check(CLI::Range(0, 100000))->capture_default_str();
  cmd->add_flag("--no-calibration", o->no_calibration, "Judged study: judge the top grasps only");
  cmd->add_flag(
      "--withhold-attitude", o->withhold_attitude,
      "Judged study: the detector is not told the camera's attitude (mount and vehicle taken "
      "as level), as for a frame with no IMU data");
  cmd->add_option(
         "--slope", o->slope_deg,
         "Judged study: the seafloor rises ahead by this many degrees (the detector is given "
         "the vehicle's attitude against gravity, pitched nose-up by it)")
      ->check(CLI::Range(-45.0, 45.0))
      ->capture_default_str();
  cmd->add_option("--sensor", o->sensors, "Judged study: rgbd (the depth camera), stereo (the rig's pair matched "
                  "into the cloud), or both")->delimiter(',')->check(CLI::IsMember({"rgbd", "stereo"}))
      ->capture_default_str();
  add_common(*cmd, o->common);
  runners.emplace_back(cmd, [o] { return run_experiments(*o); });
}

}  // namespace uwgrasp::app
