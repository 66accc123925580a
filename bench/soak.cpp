// bench/soak: detection on a long stream of simulated noisy frames in one process, as a vehicle
// would run it for hours. Each frame draws a built-in scene (thesis objects and real meshes),
// coastal or turbid water, a turn of the object of interest about the vertical and a shift of the
// vehicle, renders it with sensor noise and marine snow, and detects grasps on the object.
// Reports crashes (a crash ends the run), refusals (uwgrasp::Error, documented), other exceptions
// (must be 0), frames without a feasible grasp, resident memory at frame 100 and at the end, and
// latency (median, p95, worst frame).
//   soak [--frames N] [--seed S] [--csv FILE]     (defaults 2000, 1)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/memory.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/sim/render.hpp"

using namespace uwgrasp;

namespace {
double rss_mib() {
  std::ifstream f("/proc/self/status");
  for (std::string line; std::getline(f, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
  return 0.0;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

struct Tally {
  int frames = 0, refused = 0, other = 0, no_grasp = 0, not_in_view = 0;
  std::map<std::string, int> refusals;
  std::vector<double> ms;
};

// One frame: a scene drawn at random, turned and shifted, rendered in noisy water, detected.
void frame(const io::Config& base, const std::vector<std::string>& scenes, std::uint64_t seed, Tally& t,
           std::FILE* csv) {
  Rng rng(seed, 0x50A4);
  const std::string name = scenes[rng.below(scenes.size())];
  const char* water = rng.uniform() < 0.5 ? "coastal" : "turbid";
  app::Simulation s = app::make_simulation(base, name, water);
  std::size_t target = 0;
  for (std::size_t i = 0; i < s.scene.objects.size(); ++i)
    if (s.scene.objects[i].interest) target = i;
  const double yaw = (rng.uniform() - 0.5) * std::numbers::pi;
  auto& pose = s.scene.objects[target].pose;
  pose = Pose(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())) * pose;
  s.scene.vehicle.position += Eigen::Vector3d(rng.normal(0, 0.05), rng.normal(0, 0.05), rng.normal(0, 0.03));
  s.world_from_camera = sim::camera_pose(s.scene, s.mount);
  const sim::World world(s.scene);
  const sim::Frame f = sim::render_rgbd(world, s.world_from_camera, s.render, seed);
  io::Config cfg;
  try {
    cfg = app::pointed_at(base, s, f, target, seed);
  } catch (const Error&) {
    ++t.not_in_view;  // turned and shifted out of the camera's view: nothing to detect
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::string outcome = "ok";
  std::size_t feasible = 0;
  try {
    const grasp::Detection d = grasp::detect(f.cloud, cfg.preprocess, cfg.segment, cfg.grasp, seed);
    feasible = d.result.feasible();
    if (d.result.grasps.empty()) ++t.no_grasp, outcome = "no feasible grasp";
  } catch (const Error& e) {
    ++t.refused, ++t.refusals[std::string(e.what()).substr(0, 60)], outcome = "refused";
  } catch (const std::exception& e) {
    ++t.other, outcome = std::string("EXCEPTION ") + e.what();
    std::fprintf(stderr, "soak: frame seed %llu: %s\n", static_cast<unsigned long long>(seed), e.what());
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  t.ms.push_back(ms);
  if (csv)
    std::fprintf(csv, "%d,%s,%s,%.3f,%zu,%.1f,%s\n", t.frames, name.c_str(), water, ms, feasible, rss_mib(),
                 outcome.c_str());
}
}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  int frames = 2000;
  std::uint64_t seed = 1;
  const char* csv_path = nullptr;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--frames")) frames = std::max(101, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--seed")) seed = std::strtoull(argv[++i], nullptr, 10);
    else if (!std::strcmp(argv[i], "--csv")) csv_path = argv[++i];
  }
  std::FILE* csv = csv_path ? std::fopen(csv_path, "w") : nullptr;
  if (csv) std::fprintf(csv, "frame,scene,water,detect_ms,feasible,rss_mib,outcome\n");
  io::Config base = io::load_config("");
  base.sim.noise.enabled = true;
  const std::vector<std::string> scenes = sim::builtin_scene_names();
  Tally t;
  double rss100 = 0;
  const auto start = std::chrono::steady_clock::now();
  for (; t.frames < frames; ++t.frames) {
    frame(base, scenes, seed + std::uint64_t(t.frames), t, csv);
    if (t.frames + 1 == 100) rss100 = rss_mib();
    if ((t.frames + 1) % 50 == 0)
      std::fprintf(stderr, "soak: %d/%d frames, %.0f s, RSS %.1f MiB, other exceptions %d\n", t.frames + 1, frames,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), rss_mib(),
                   t.other);
  }
  if (csv) std::fclose(csv);
  const double rss_end = rss_mib();
  std::printf("| frames | detected | refused (Error) | other exceptions | no feasible grasp | out of view | "
              "RSS @100 MiB | RSS @%d MiB | growth | median ms | p95 ms | worst ms |\n", frames);
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::printf("| %d | %zu | %d | %d | %d | %d | %.1f | %.1f | %+.2f %% | %.0f | %.0f | %.0f |\n", frames, t.ms.size(),
              t.refused, t.other, t.no_grasp, t.not_in_view, rss100, rss_end, 100.0 * (rss_end - rss100) / rss100,
              quantile(t.ms, 0.5), quantile(t.ms, 0.95), quantile(t.ms, 1.0));
  for (const auto& [what, n] : t.refusals) std::printf("refused %d x: %s\n", n, what.c_str());
  return t.other == 0 ? 0 : 1;
}
