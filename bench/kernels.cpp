// Google Benchmark kernels of the cloud/ and segment/ stages on the generated seafloor scene.
#include <benchmark/benchmark.h>

#include "scene.hpp"
#include "uwgrasp/cloud/filters.hpp"
#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/cloud/normals.hpp"
#include "uwgrasp/cloud/outliers.hpp"
#include "uwgrasp/cloud/ransac.hpp"
#include "uwgrasp/cloud/voxel.hpp"
#include "uwgrasp/segment/pipeline.hpp"

using namespace uwgrasp;

namespace {
const Cloud& scene() {
  static const Cloud c = bench::seafloor_scene();
  return c;
}
const Cloud& finite() {
  static const Cloud c = cloud::remove_invalid(scene()).cloud;
  return c;
}
}  // namespace

static void BM_Finite(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(cloud::remove_invalid(scene()));
}
static void BM_KdTreeBuild(benchmark::State& s) {
  for (auto _ : s) {
    const cloud::KdTree t(finite().points);
    benchmark::DoNotOptimize(t.size());
  }
}
static void BM_Voxel(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(cloud::voxel_grid(finite(), {true, 0.01f, 1}));
}
static void BM_Outliers(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(cloud::remove_outliers(finite(), {true, 10, 1.0}));
}
static void BM_Ransac(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(cloud::fit_plane(finite(), {}, 1));
}
static void BM_Normals(benchmark::State& s) {
  Cloud c = finite();
  for (auto _ : s) cloud::compute_normals(c, {20, 0});
}
static void BM_WholeChain(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(segment::segment_scene(scene(), {}, {}, 1));
}
BENCHMARK(BM_Finite)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KdTreeBuild)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Voxel)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Outliers)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Ransac)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Normals)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WholeChain)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
