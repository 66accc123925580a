#pragma once
// Options every subcommand shares, and the error policy of the CLI.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "uwgrasp/io/config.hpp"

namespace uwgrasp::app {

struct CommonOptions {
  std::string config_path;
  std::vector<std::string> sets;
  std::int64_t seed = -1;     // -1: from config
  std::int64_t threads = -1;  // -1: from config
};

// Adds --config, --set, --seed and --threads to a subcommand.
void add_common(CLI::App& cmd, CommonOptions& opt);

// The effective config: defaults <- --config <- --set <- --seed/--threads. Limits TBB to the
// configured thread count for the life of the returned guard.
struct Session {
  io::Config config;
  std::shared_ptr<void> thread_limit;
};
Session open_session(const CommonOptions& opt);

// A preset from config/: the source tree's when run from a build, else the installed copy.
std::string preset_path(const std::string& file);

// Creates DIR and its parents; throws Error (exit 2) when that fails, e.g. DIR is a file.
void make_output_dir(const std::string& dir);

// Milliseconds since t0.
double ms_since(std::chrono::steady_clock::time_point t0);

// Writes one line to stderr when stderr is a terminal or --progress asked for it.
void progress(const std::string& line);

// Registers a subcommand; `run` is called when it was chosen and returns the exit code.
using Runner = std::function<int()>;
void add_segment_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners);
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
