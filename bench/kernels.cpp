// Google Benchmark kernels of the cloud/ and segment/ stages on the generated seafloor scene, of
// the organised path's stages on a 640 x 480 frame of it (or on the organised .pcd that
// UWGRASP_BENCH_FRAME names, e.g. a mOSD_learn frame), and of the grasp engine on the thesis's
// barbell (64,648 points, one-sided).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <optional>

#include "objects.hpp"
#include "scene.hpp"
#include "uwgrasp/cloud/filters.hpp"
#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/cloud/normals.hpp"
#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/outliers.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/cloud/ransac.hpp"
#include "uwgrasp/cloud/voxel.hpp"
#include "uwgrasp/core/memory.hpp"
#include "uwgrasp/grasp/debris.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/pcd.hpp"
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
// The barbell in the level frame and 3000 candidates from Table 8.5's barbell preset.
struct Barbell {
  std::vector<Eigen::Vector3f> points;
  std::vector<grasp::Candidate> candidates;
  grasp::Gripper gripper = grasp::make_gripper({});
};
const Barbell& barbell() {
  static const Barbell b = [] {
    Barbell out;
    const auto obj = fixtures::render_object(fixtures::Object::barbell, {}, 64648);
    grasp::FrameConfig fc;
    fc.camera.rpy.y() = obj.camera_pitch;
    const grasp::Frames f = grasp::make_frames(fc);
    out.points = grasp::points_to_level(obj.cloud.points, f);
    out.candidates = grasp::sample_normal(out.points, {}, f.body_from_gripper.linear(), 1, 3000);
    return out;
  }();
  return b;
}
// A 640 x 480 frame of the scene after the organised path's plane stage (outlier removal off, so
// every point the plane left is here) and the map of its pixels: the input of the window stages.
struct Frame {
  Cloud raw = std::getenv("UWGRASP_BENCH_FRAME") ? io::load_cloud(std::getenv("UWGRASP_BENCH_FRAME"))
                                                 : bench::seafloor_scene(640, 480);
  Cloud cloud;
  cloud::PixelMap map;
  std::optional<Eigen::Vector4f> plane;  // the plane the preprocessing removed, if it found one
};
const Frame& frame() {
  static const Frame f = [] {
    keep_freed_memory();  // a stream of frames, as bench/frame runs them
    Frame out;
    cloud::PreprocessConfig cfg;
    cfg.outliers.enabled = false;
    StageTimer timer;
    cloud::Preprocessed pre = cloud::preprocess(out.raw, cfg, 1, timer);
    std::vector<std::uint32_t> pixel(pre.cloud.size());
    for (std::size_t i = 0; i < pre.output_of_input.size(); ++i)
      if (pre.output_of_input[i] >= 0) pixel[std::size_t(pre.output_of_input[i])] = std::uint32_t(i);
    out.map = cloud::pixel_map(out.raw.width, out.raw.height, std::move(pixel));
    out.cloud = std::move(pre.cloud);
    if (pre.plane.found) out.plane = pre.plane.coefficients;
    return out;
  }();
  return f;
}
}  // namespace

// The organised path, stage by stage, on the 640 x 480 frame.
static void BM_OrgPreprocess(benchmark::State& s) {
  for (auto _ : s) {
    StageTimer timer;
    benchmark::DoNotOptimize(cloud::preprocess(frame().raw, {}, 1, timer));
    for (const auto& st : timer.stages()) s.counters[st.name] += st.ms;
  }
  for (auto& [name, c] : s.counters) c = c.value / double(s.iterations());
}
static void BM_OrgWindowLists(benchmark::State& s) {
  for (auto _ : s)
    benchmark::DoNotOptimize(cloud::window_neighbours(frame().cloud.points, frame().map, {}, frame().cloud.viewpoint));
}
static void BM_OrgOutlierStatistic(benchmark::State& s) {
  for (auto _ : s)
    benchmark::DoNotOptimize(cloud::window_mean_distances(frame().cloud.points, frame().map, 2, 10));
}
static void BM_OrgNormals(benchmark::State& s) {
  Cloud c = frame().cloud;
  for (auto _ : s) cloud::window_normals(c, frame().map, {});
}
// The normals of a 9 x 9 window, and the move onto quadratics fitted to the windows' ranges (a
// frame whose window grew: a noisier sensor's, e.g. UWGRASP_BENCH_FRAME a simulated frame with
// sim.noise.sigma_k 0.008).
static void BM_OrgNormals9(benchmark::State& s) {
  cloud::OrganisedConfig cfg;
  cfg.normal_half_window = 4;
  Cloud c = frame().cloud;
  cloud::WindowScratch scratch;
  for (auto _ : s) cloud::window_normals(c, frame().map, cfg, scratch);
}
static void BM_OrgMoveOntoQuadrics(benchmark::State& s) {
  cloud::OrganisedConfig cfg;
  cfg.normal_half_window = 4;
  cloud::WindowScratch scratch;
  Cloud c;
  for (auto _ : s) {
    s.PauseTiming();
    c = frame().cloud;
    s.ResumeTiming();
    benchmark::DoNotOptimize(cloud::move_onto_quadrics(c, frame().map, cfg, scratch));
  }
}
static void BM_OrgSegments(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(segment::segment_scene(frame().raw, {}, {}, 1));
}

// The whole object `largest` selects on the frame's segments: its connected objects and the
// parts within segment.object.part_reach gathered to it (detect's `select` stage).
static void BM_WholeObject(benchmark::State& s) {
  static const segment::Scene seen = segment::segment_scene(frame().raw, {}, {}, 1);
  segment::ObjectConfig cfg;
  cfg.by = segment::ObjectBy::largest;
  std::size_t selected = 0;
  for (auto _ : s) benchmark::DoNotOptimize(grasp::object_points(seen, cfg, selected));
}

// The reach check's marine-snow filter over the frame's processed points (the detector gives it
// the whole processed scene, e.g. 85,000 points on the real mug frame).
static void BM_Debris(benchmark::State& s) {
  for (auto _ : s)
    benchmark::DoNotOptimize(grasp::debris(frame().cloud.points, frame().plane, 0.01f, 0.02f));
}

static void BM_BvhBuild(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(grasp::build_bvh(barbell().points));
}
static void BM_Check3000(benchmark::State& s) {
  const grasp::PointBvh bvh = grasp::build_bvh(barbell().points);
  for (auto _ : s)
    benchmark::DoNotOptimize(grasp::check_candidates(bvh, barbell().gripper, barbell().candidates));
}
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
BENCHMARK(BM_OrgPreprocess)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OrgWindowLists)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OrgOutlierStatistic)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OrgNormals)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OrgNormals9)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OrgMoveOntoQuadrics)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OrgSegments)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_WholeObject)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Debris)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhBuild)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Check3000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
