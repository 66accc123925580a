// uwgrasp experiments [--iterations N] --out DIR: the thesis's chapter 8 on the simulated scenes
// in clear water with a perfect sensor (the thesis's conditions), then in coastal and turbid
// water with a realistic sensor; writes DIR/report.md and its figures.
#include <iostream>

#include "app/common.hpp"
#include "commands.hpp"
#include "experiments/experiments.hpp"

namespace uwgrasp::app {

namespace {
struct ExperimentOptions {
  CommonOptions common;
  std::string out;
  int iterations = 50;
  std::vector<std::string> waters = {"clear", "coastal", "turbid"};
  std::string command;  // as typed, for the report
};

int run_experiments(const ExperimentOptions& o) {
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
  cmd->add_option("--water", o->waters, "Water conditions to study: clear (perfect sensor), coastal, turbid")
      ->check(CLI::IsMember({"clear", "coastal", "turbid"}))->capture_default_str();
  add_common(*cmd, o->common);
  runners.emplace_back(cmd, [o] { return run_experiments(*o); });
}

}  // namespace uwgrasp::app
