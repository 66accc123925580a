// uwgrasp: grasp poses for an underwater vehicle with a rigidly mounted (0-DoF) gripper.
// Exit codes: 0 success, 2 bad input or usage, 1 internal error.
#include <iostream>

#include "app/common.hpp"
#include "commands.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/memory.hpp"
#include "uwgrasp/io/atomic_file.hpp"

int main(int argc, char** argv) {
  using namespace uwgrasp::app;
  uwgrasp::keep_freed_memory();  // experiments and bags run many frames in one process
  // Interrupted runs leave every output as it was or complete, and no temporary file.
  uwgrasp::io::remove_partial_outputs_on_signal();
  CLI::App app{"uwgrasp " UWGRASP_VERSION
               " - grasp poses for an underwater vehicle with a rigidly mounted gripper"};
  app.require_subcommand(1, 1);
  app.set_version_flag("--version", UWGRASP_VERSION);
  std::vector<std::pair<CLI::App*, Runner>> runners;
  add_demo_command(app, runners);
  add_detect_command(app, runners);
  add_simulate_command(app, runners);
  add_evaluate_command(app, runners);
  add_experiments_command(app, runners, argc, argv);
  add_approach_command(app, runners);
  add_segment_command(app, runners);
  add_calibrate_command(app, runners);
  add_stereo_commands(app, runners);
  add_config_command(app, runners);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "uwgrasp: " << e.what() << " (see uwgrasp --help)\n";
    return 2;
  }
  try {
    for (auto& [cmd, run] : runners)
      if (cmd->parsed()) return run();
  } catch (const uwgrasp::Error& e) {
    std::cerr << "uwgrasp: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "uwgrasp: internal error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
