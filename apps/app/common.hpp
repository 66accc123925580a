#pragma once
// What the CLI's subcommands and the studies share: common options, the effective config,
// output folders and progress lines.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "uwgrasp/core/error.hpp"
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

// f(), with the input's name before the message of an Error it throws: a refusal of what the
// file holds ("no finite point", "no segment to grasp") then names the file, as a refusal to
// read it does.
template <class F>
decltype(auto) about_input(const std::string& name, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    throw Error(name + ": " + e.what());
  }
}

}  // namespace uwgrasp::app
