#pragma once
// The CLI's subcommands: each file cmd_NAME.cpp registers one.
#include <CLI/CLI.hpp>
#include <functional>
#include <utility>
#include <vector>

namespace uwgrasp::app {

// Registers a subcommand; `run` is called when it was chosen and returns the exit code.
using Runner = std::function<int()>;
void add_segment_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners);
void add_calibrate_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners);
void add_stereo_commands(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners);
void add_config_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners);
void add_approach_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners);
void add_detect_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners);
void add_demo_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners);
void add_evaluate_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners);
void add_simulate_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners);
// Also records the command line for its report.
void add_experiments_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners,
                             int argc, char** argv);

}  // namespace uwgrasp::app
