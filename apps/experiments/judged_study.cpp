// The judged study (judged_study.hpp): render, detect with the plan's settings, judge.
#include "experiments/judged_study.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <iostream>

#include "app/common.hpp"
#include "app/judged_picture.hpp"
#include "app/sensor.hpp"
#include "experiments/experiments_report.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/scene.hpp"

namespace uwgrasp::experiments {

namespace {
int interest(const sim::Scene& s) {
  for (std::size_t i = 0; i < s.objects.size(); ++i)
    if (s.objects[i].interest) return int(i);
  throw Error("scene " + s.name + ": the judged study needs an object of interest");
}

struct Setting {
  const Simulation& sim;
  const sim::World& world;
  int target = 0;
};

// Judges every grasp beyond the top ones too, for the calibration of the detector's scores.
void score_outcomes(const Setting& st, const eval::Camera& cam, const grasp::Gripper& g,
                    const grasp::Detection& d, std::span<const Pose> poses,
                    const eval::Evaluation& e, double mu, std::vector<ScoredOutcome>& out) {
  const auto& grasps = d.result.grasps;
  std::vector<ScoredOutcome> scored(grasps.size());
  tbb::parallel_for(std::size_t(0), grasps.size(), [&](std::size_t i) {
    const eval::Judgement j = i < e.judgements.size() ? e.judgements[i]
                                                      : eval::judge(st.world, cam, g, poses[i], st.target);
    scored[i] = {grasps[i].scores, grasps[i].friction.mu_required, grasps[i].robustness,
                 grasps[i].force_closure,
                 j.verdict == eval::Verdict::closes ? j.mu_min : std::numeric_limits<double>::infinity(),
                 j.holds(mu)};
  });
  out.insert(out.end(), scored.begin(), scored.end());
}

// The stereo sensor's cloud in place of the depth camera's (`f`, rendered ideal: the truth), and
// its depth against that truth. Returns the matcher's depth error at 1 m (DenseFrame).
double use_stereo(const Setting& st, const JudgedPlan& plan, std::uint64_t seed, sim::Frame& f,
                  JudgedRun& run) {
  const sim::StereoFrame s = sim::render_stereo(st.world, st.sim.world_from_camera, st.sim.render, seed);
  camera::DenseFrame matched = simulated_stereo(s, plan.base.stereo);
  const DepthAccuracy a = depth_accuracy(matched.cloud, f, sim::kLabelFirstObject + st.target, 1e9);
  run.depth_error = a.median_error, run.completeness = a.completeness;
  f.cloud = std::move(matched.cloud);
  return matched.depth_error;
}

// The detector's settings for one run: the plan's, with the run's seed, the simulated camera's
// frames, the matcher's depth error, and what the plan withholds or tilts.
io::Config run_config(const Setting& st, const JudgedPlan& plan, std::uint64_t seed,
                      double matcher_error) {
  io::Config cfg = plan.base;
  use_matcher_error(cfg.grasp.shape, matcher_error);  // as detecting from a stereo pair does
  cfg.seed = seed;
  use_simulation_frames(cfg, st.sim);
  if (plan.withhold_attitude) {
    cfg.grasp.frames.camera.rpy.setZero();
    cfg.grasp.frames.capture_roll = cfg.grasp.frames.capture_pitch = 0.0;
    cfg.grasp.frames.level_from_floor = plan.base.grasp.frames.level_from_floor;  // as for a file
  }
  cfg.grasp.frames.capture_pitch += plan.slope;
  if (plan.calibrate) cfg.grasp.score.top = std::max<std::uint32_t>(cfg.grasp.score.top, 1000000);
  return cfg;
}

// The case's picture tile: its first run's judged grasps.
cv::Mat tile(const Setting& st, const JudgedPlan& plan, const JudgedCase& c,
             const eval::Camera& cam, const grasp::Gripper& g, std::span<const Pose> poses,
             const eval::Evaluation& e, std::uint64_t seed, std::size_t feasible) {
  viz::Picture pic;
  pic.title = st.sim.scene.name + ", " + c.label();
  pic.legend.push_back(fmt("seed %llu: top %zu of %zu feasible grasps",
                           static_cast<unsigned long long>(seed), e.judgements.size(), feasible));
  viz::View view;
  view.width = 640, view.height = 480;
  return judged_picture(st.world, cam, g, poses.first(e.judgements.size()), e.judgements, st.target,
                        plan.summary.reference_mu, pic, view);
}

JudgedRun run_once(const Setting& st, const JudgedPlan& plan, std::uint64_t seed,
                   JudgedCaseResult& out, bool first) {
  JudgedRun run;
  const bool stereo = out.c.sensor == "stereo";
  sim::RenderConfig depth_camera = st.sim.render;
  if (stereo) depth_camera.noise.enabled = false;  // only the truth is needed from it
  sim::Frame f = sim::render_rgbd(st.world, st.sim.world_from_camera, depth_camera, seed);
  run.visible_points = std::size_t(std::count(f.labels.begin(), f.labels.end(),
                                              std::uint16_t(sim::kLabelFirstObject + st.target)));
  const double matcher_error = stereo ? use_stereo(st, plan, seed, f, run) : 0.0;
  const io::Config cfg = run_config(st, plan, seed, matcher_error);
  const auto t0 = std::chrono::steady_clock::now();
  grasp::Detection d;
  try {
    d = grasp::detect(f.cloud, cfg.preprocess, cfg.segment, cfg.grasp, seed);
  } catch (const Error& e) {
    run.error = e.what();
    run.summary = eval::summarise({}, plan.summary);
    return run;
  }
  run.detect_ms = ms_since(t0);
  run.feasible = d.result.feasible();
  run.candidates = d.result.candidates;
  run.object_points = d.object.size();
  const auto t1 = std::chrono::steady_clock::now();
  const eval::Camera cam{st.sim.world_from_camera, f.intrinsics, st.sim.render.camera.max_range};
  const grasp::Gripper g = grasp::make_gripper(cfg.grasp.gripper);
  std::vector<Pose> poses;
  for (const auto& gr : d.result.grasps)
    poses.push_back(st.sim.world_from_camera * grasp::camera_from_gripper(gr, d.result.frames));
  const eval::Evaluation e = eval::evaluate(st.world, cam, g, poses, st.target, plan.summary, plan.robust, seed);
  run.summary = e.summary;
  run.robust = e.robust_top1;
  run.has_top1 = !e.judgements.empty();
  if (run.has_top1) {
    run.top1 = e.judgements.front();
    const grasp::Grasp& best = d.result.grasps.front();
    run.predicted_mu = best.friction.mu_required;
    run.predicted_robustness = best.robustness;
    run.predicted_width = best.width;
    run.contact_seen[0] = best.contact_seen[0], run.contact_seen[1] = best.contact_seen[1];
  }
  if (plan.calibrate) score_outcomes(st, cam, g, d, poses, e, plan.summary.reference_mu, out.scored);
  run.judge_ms = ms_since(t1);
  if (first) out.tile = tile(st, plan, out.c, cam, g, poses, e, seed, run.feasible);
  return run;
}
}  // namespace

std::vector<std::string> held_in_scenes() {
  std::vector<std::string> out;
  for (const auto& n : sim::builtin_scene_names())
    if (n != "barbell" && n != "ring" && n != "cross" && n != "thesis" && n != "several") out.push_back(n);
  return out;
}

std::vector<std::string> thesis_object_scenes() { return {"barbell", "ring", "cross"}; }

std::vector<JudgedCaseResult> run_judged_study(const JudgedPlan& plan) {
  std::vector<JudgedCaseResult> results;
  for (const JudgedCase& c : plan.cases) {
    io::Config cfg = plan.base;
    cfg.sim.noise.enabled = c.noise;
    const Simulation s = make_simulation(cfg, c.scene, c.water);
    const sim::World world(s.scene);
    const Setting st{s, world, interest(s.scene)};
    JudgedCaseResult r;
    r.c = c;
    const auto t0 = std::chrono::steady_clock::now();
    const eval::Camera camera{s.world_from_camera, sim::make_intrinsics(s.render.camera), s.render.camera.max_range};
    r.grasp_exists =
        eval::find_any_grasp(world, camera, grasp::make_gripper(plan.base.grasp.gripper), st.target).exists;
    for (int i = 0; i < plan.iterations; ++i) {
      std::cerr << "uwgrasp experiments [judged] " << c.scene << ", " << c.label() << ": iteration " << i + 1
                << "/" << plan.iterations << std::endl;
      r.runs.push_back(run_once(st, plan, plan.base.seed + std::uint64_t(i), r, i == 0));
    }
    r.seconds = ms_since(t0) / 1000.0;
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace uwgrasp::experiments
