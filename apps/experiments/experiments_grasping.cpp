// Table 8.3 (5000 candidates per sampler and object: time, collision-free and feasible share),
// Table 8.5's presets at work and figures 8.13-8.16 (the best grasp of every iteration), thesis
// 8.3 and 8.5, on the thesis scene with its three objects.
#include <algorithm>
#include <chrono>

#include "app/common.hpp"
#include "experiments/experiments.hpp"
#include "uwgrasp/cloud/color.hpp"
#include "uwgrasp/eval/evaluate.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::experiments {

namespace {
constexpr std::uint32_t kTable83Samples = 5000;
constexpr grasp::SamplerKind kSamplers[] = {grasp::SamplerKind::normal, grasp::SamplerKind::uniform,
                                            grasp::SamplerKind::surface};

// Candidates that no solid part of the gripper collides with (the thesis's "collision-free").
std::size_t collision_free(const grasp::ObjectGrasps& r) {
  using grasp::Reject;
  std::size_t hit = 0;
  for (Reject k : {Reject::collision_left_finger, Reject::collision_right_finger, Reject::collision_palm,
                   Reject::collision_body})
    hit += r.rejections[static_cast<std::size_t>(k)];
  return r.candidates - hit;
}

// Table 8.3 on one object cloud: every sampler with the object's preset otherwise, its top 10
// judged against the truth.
void sample_rows(const sim::World& world, const sim::Frame& f, std::size_t o, const grasp::Detection& d,
                 const io::Config& oc, std::uint64_t seed, std::vector<SamplerRow>& rows, std::size_t first) {
  const double leaf = oc.preprocess.voxel.enabled ? oc.preprocess.voxel.leaf : 0.0;
  for (std::size_t k = 0; k < std::size(kSamplers); ++k) {
    grasp::GraspConfig gc = oc.grasp;
    gc.sampler.kind = kSamplers[k];
    gc.sampler.samples = kTable83Samples;
    gc.score.top = 10;
    StageTimer t;
    grasp::Detection dk;
    dk.result = grasp::find_grasps(d.object, gc, leaf, seed, t);
    const grasp::ObjectGrasps& r = dk.result;
    SamplerRow& row = rows[first + k];
    row.judged.push_back(judge_detection(world, f, dk, int(o), gc.gripper, seed));
    row.sample_ms.push_back(t.ms("sample"));
    row.collision_free.push_back(double(collision_free(r)));
    row.feasible.push_back(double(r.feasible()));
  }
}

void note_failure(FinalObject& fo, const std::string& what) {
  ++fo.failures;
  fo.judged.push_back({eval::summarise({}, {}), "no grasp"});
  if (std::find(fo.errors.begin(), fo.errors.end(), what) == fo.errors.end() && fo.errors.size() < 3)
    fo.errors.push_back(what);
}

void detect_once(const Simulation& s, const sim::World& world, const sim::Frame& f, std::size_t o,
                 const ExperimentPlan& plan, std::uint64_t seed, ConditionResult& out) {
  FinalObject& fo = out.finals[o];
  try {
    const io::Config preset = object_config(s, f, o, plan.sets, seed);
    io::Config oc = preset;
    oc.grasp.reach.enabled = false;  // the thesis checked the gripper against the object only
    const auto t0 = std::chrono::steady_clock::now();
    const grasp::Detection d = grasp::detect(f.cloud, oc.preprocess, oc.segment, oc.grasp, seed);
    fo.detect_ms.push_back(ms_since(t0));
    fo.feasible.push_back(double(d.result.feasible()));
    const auto label = static_cast<std::uint16_t>(sim::kLabelFirstObject + o);
    const auto visible = std::count(f.labels.begin(), f.labels.end(), label);
    fo.coverage.push_back(double(d.object.size()) / double(std::max<std::ptrdiff_t>(visible, 1)));
    fo.judged.push_back(judge_detection(world, f, d, int(o), oc.grasp.gripper, seed));
    if (!d.result.grasps.empty()) {
      fo.best.push_back(d.result.grasps.front());
      fo.vehicle.push_back(run_vehicle(d, d.result.grasps.front(), preset));
    }
    if (fo.view.empty()) {
      fo.cfg = oc;
      fo.frames = d.result.frames;
      fo.view = f.cloud;
      // With colour restoration on, draw what the pipeline saw: the object in its own colours.
      if (oc.preprocess.water.enabled) cloud::restore_colors(fo.view, oc.preprocess.water);
      fo.focus = d.object.points;
    }
    sample_rows(world, f, o, d, oc, seed, out.sampling, o * std::size(kSamplers));
  } catch (const Error& e) {
    note_failure(fo, e.what());
  }
}
}  // namespace

void run_sampling_study(const ExperimentPlan& plan, const Condition& c, ConditionResult& out) {
  io::Config cfg = plan.base;
  cfg.sim.noise.enabled = c.noise;
  const Simulation s = make_simulation(cfg, "thesis", c.water);
  const sim::World world(s.scene);
  out.finals.assign(s.scene.objects.size(), {});
  out.sampling.clear();
  for (std::size_t o = 0; o < s.scene.objects.size(); ++o) {
    out.finals[o].name = s.scene.objects[o].name;
    for (const auto k : kSamplers) out.sampling.push_back({s.scene.objects[o].name, k, kTable83Samples, {}, {}, {}, {}});
  }
  for (int i = 0; i < plan.iterations; ++i) {
    experiment_step(c, "tables 8.3/8.5, figures 8.13-8.16", i, plan.iterations);
    const std::uint64_t seed = plan.base.seed + static_cast<std::uint64_t>(i);
    const sim::Frame f = sim::render_rgbd(world, s.world_from_camera, s.render, seed);
    for (std::size_t o = 0; o < s.scene.objects.size(); ++o) detect_once(s, world, f, o, plan, seed, out);
  }
}

Judged judge_detection(const sim::World& world, const sim::Frame& f, const grasp::Detection& d,
                       int target, const grasp::GripperConfig& gripper, std::uint64_t seed) {
  const eval::Camera cam{f.world_from_camera, f.intrinsics, 6.0};
  std::vector<Pose> poses;
  for (const auto& g : d.result.grasps)
    poses.push_back(f.world_from_camera * grasp::camera_from_gripper(g, d.result.frames));
  eval::RobustConfig no_robust;
  no_robust.samples = 0;
  const eval::SummaryConfig sc;
  const eval::Evaluation e = eval::evaluate(world, cam, grasp::make_gripper(gripper), poses, target, sc, no_robust, seed);
  return {e.summary, e.judgements.empty() ? "no grasp" : eval::outcome_name(eval::outcome(e.judgements[0], sc.reference_mu))};
}

}  // namespace uwgrasp::experiments
