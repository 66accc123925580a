// Google Benchmark: the simulator's RGB-D camera on the thesis scene (target <= 50 ms per
// 640 x 480 frame), with the noise and marine snow on and off, and building the scene's BVH.
#include <benchmark/benchmark.h>

#include "uwgrasp/sim/render.hpp"

namespace {
using namespace uwgrasp;

sim::RenderConfig config(const std::string& water, bool noise) {
  sim::RenderConfig c;
  c.water = sim::water_preset(water);
  c.noise.enabled = noise;
  return c;
}

void render(benchmark::State& s, const std::string& water, bool noise) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const sim::World world(scene);
  const Pose wc = sim::camera_pose(scene, Mount{});
  const sim::RenderConfig cfg = config(water, noise);
  std::uint64_t seed = 1;
  for (auto _ : s) benchmark::DoNotOptimize(sim::render_rgbd(world, wc, cfg, seed++));
}

void BM_RenderThesisPerfect(benchmark::State& s) { render(s, "clear", false); }
void BM_RenderThesisClear(benchmark::State& s) { render(s, "clear", true); }
void BM_RenderThesisTurbid(benchmark::State& s) { render(s, "turbid", true); }
void BM_BuildThesisWorld(benchmark::State& s) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  for (auto _ : s) benchmark::DoNotOptimize(sim::World(scene));
}
}  // namespace

BENCHMARK(BM_RenderThesisPerfect)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderThesisClear)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderThesisTurbid)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BuildThesisWorld)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
