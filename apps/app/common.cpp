#include "app/common.hpp"

#include <filesystem>

#include "uwgrasp/core/error.hpp"

#include <tbb/global_control.h>
#include <unistd.h>

#include <iostream>

namespace uwgrasp::app {

void add_common(CLI::App& cmd, CommonOptions& opt) {
  cmd.add_option("--config", opt.config_path, "YAML config file (defaults: config/default.yaml)")
      ->check(CLI::ExistingFile);
  cmd.add_option("--set", opt.sets, "Override a config value: section.key=value (repeatable)");
  cmd.add_option("--seed", opt.seed, "Random seed (same seed, same output)")->check(CLI::NonNegativeNumber);
  cmd.add_option("--threads", opt.threads, "Worker threads (0: all cores)")->check(CLI::Range(0, 4096));
}

Session open_session(const CommonOptions& opt) {
  Session s;
  s.config = io::load_config(opt.config_path, opt.sets);
  if (opt.seed >= 0) s.config.seed = static_cast<std::uint64_t>(opt.seed);
  if (opt.threads >= 0) s.config.threads = static_cast<std::uint32_t>(opt.threads);
  if (s.config.threads > 0) {
    s.thread_limit = std::make_shared<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, s.config.threads);
  }
  return s;
}

std::string preset_path(const std::string& file) {
  for (const char* dir : {UWGRASP_SOURCE_CONFIG_DIR, UWGRASP_INSTALLED_CONFIG_DIR}) {
    const std::filesystem::path p = std::filesystem::path(dir) / file;
    std::error_code ec;
    if (std::filesystem::is_regular_file(p, ec)) return p.string();
  }
  throw Error("preset " + file + " not found in " UWGRASP_SOURCE_CONFIG_DIR " or " UWGRASP_INSTALLED_CONFIG_DIR);
}

void make_output_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw Error(dir + ": cannot create output directory" + (ec ? " (" + ec.message() + ")" : ""));
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void progress(const std::string& line) {
  if (::isatty(STDERR_FILENO)) std::cerr << line << "\n";
}

}  // namespace uwgrasp::app
