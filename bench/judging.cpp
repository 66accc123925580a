// Ground-truth judging speed (issue target: 100 grasps with 25 perturbations each in <= 1 s):
// the top 100 feasible grasps the detector finds on an object of the thesis scene, each judged
// once and under 25 perturbed poses, on the thesis's primitives and on a YCB mesh (16k triangles).
#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>

#include <filesystem>
#include <iostream>

#include "uwgrasp/eval/judge.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/sim/render.hpp"

using namespace uwgrasp;

namespace {
struct Case {
  sim::Scene scene;
  std::unique_ptr<sim::World> world;
  eval::Camera camera;
  std::vector<Pose> grasps;  // T_WG
  int target = 0;
};

// Renders the scene (perfect sensor), detects on the object of interest and keeps 100 grasps.
Case make_case(sim::Scene scene) {
  Case c;
  c.scene = std::move(scene);
  c.world = std::make_unique<sim::World>(c.scene);
  sim::RenderConfig rc;
  rc.noise.enabled = false;
  const Pose T_WC = sim::camera_pose(c.scene, {});
  const sim::Frame f = sim::render_rgbd(*c.world, T_WC, rc, 1);
  c.camera = {T_WC, f.intrinsics, 6.0};
  for (std::size_t i = 0; i < c.scene.objects.size(); ++i)
    if (c.scene.objects[i].interest) c.target = int(i);
  grasp::GraspConfig gc;
  gc.frames.camera = *c.scene.camera_mount;
  grasp::given_attitude(gc.frames, c.scene.vehicle.rpy.x(), c.scene.vehicle.rpy.y());
  gc.sampler.kind = grasp::SamplerKind::uniform;
  gc.sampler.samples = 20000;
  gc.score.top = 100;
  cloud::PreprocessConfig pre;
  segment::SegmentConfig seg;
  const grasp::Detection d = grasp::detect(f.cloud, pre, seg, gc, 1);
  for (const auto& g : d.result.grasps) c.grasps.push_back(T_WC * grasp::camera_from_gripper(g, d.result.frames));
  return c;
}

void judge_all(benchmark::State& s, const Case& c) {
  const grasp::Gripper g = grasp::make_gripper({});
  const eval::RobustConfig rc;  // 25 poses, 5 mm, 3 deg
  std::vector<double> robust(c.grasps.size());
  for (auto _ : s) {
    tbb::parallel_for(std::size_t(0), c.grasps.size(), [&](std::size_t i) {
      benchmark::DoNotOptimize(eval::judge(*c.world, c.camera, g, c.grasps[i], c.target));
      robust[i] = eval::robust_share(*c.world, c.camera, g, c.grasps[i], c.target, rc, 1, i);
    });
  }
  s.counters["grasps"] = double(c.grasps.size());
  s.counters["judgements"] = double(c.grasps.size() * (rc.samples + 1));
}
}  // namespace

static void BM_Judge100x25Barbell(benchmark::State& s) {
  static const Case c = make_case(sim::builtin_scene("barbell"));
  judge_all(s, c);
}
BENCHMARK(BM_Judge100x25Barbell)->Unit(benchmark::kMillisecond)->UseRealTime();

static void BM_Judge100x25Ring(benchmark::State& s) {
  static const Case c = make_case(sim::builtin_scene("ring"));
  judge_all(s, c);
}
BENCHMARK(BM_Judge100x25Ring)->Unit(benchmark::kMillisecond)->UseRealTime();

static void BM_Judge100x25SugarBox(benchmark::State& s) {
  const std::string file = UWGRASP_DATA_DIR "/meshes/ycb/004_sugar_box_textured.obj";
  if (!std::filesystem::exists(file)) {
    s.SkipWithError(("mesh not found: " + file).c_str());
    return;
  }
  static const Case c = [&] {
    sim::Scene sc = sim::builtin_scene("barbell");
    sc.name = "sugar_box";
    sc.objects[0] = {"sugar_box", {{sim::Shape{.kind = sim::ShapeKind::mesh, .file = file}, Pose::Identity()}},
                     Pose::Identity(), {210, 25, 25}, true};
    return make_case(sc);
  }();
  judge_all(s, c);
}
BENCHMARK(BM_Judge100x25SugarBox)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
