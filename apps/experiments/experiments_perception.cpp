// Tables 8.1, 8.2 (segmentation of the barbell scene without and with RANSAC) and 8.4
// (collision checking 3000 candidates with and without 2.5 mm voxels), thesis 8.2 and 8.4.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "app/common.hpp"
#include "experiments/experiments.hpp"
#include "uwgrasp/cloud/voxel.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/frames.hpp"

namespace uwgrasp::experiments {

namespace {
constexpr double kThesisObjectPoints = 64648;  // the barbell cloud of thesis Figure 8.8a

Simulation barbell_simulation(const ExperimentPlan& plan, const Condition& c) {
  io::Config cfg = plan.base;
  cfg.sim.noise.enabled = c.noise;
  return make_simulation(cfg, "barbell", c.water);
}

// Intersection over union with the pixels whose truth label is `truth`: of the segment that
// matches best, and of the union of `chosen` segments.
struct Iou {
  double best = 0, chosen = 0;
};
Iou truth_iou(std::span<const std::int32_t> segment_of, std::span<const std::uint16_t> labels,
              std::uint16_t truth, const std::vector<std::size_t>& chosen) {
  std::int32_t top = -1;
  for (const auto s : segment_of) top = std::max(top, s);
  std::vector<std::size_t> size(static_cast<std::size_t>(top + 1), 0), both(size);
  std::size_t truth_size = 0;
  for (std::size_t p = 0; p < segment_of.size(); ++p) {
    const bool t = labels[p] == truth;
    truth_size += t;
    if (segment_of[p] < 0) continue;
    ++size[static_cast<std::size_t>(segment_of[p])];
    both[static_cast<std::size_t>(segment_of[p])] += t;
  }
  const auto iou = [&](std::size_t n, std::size_t in) { return double(in) / double(n + truth_size - in); };
  Iou out;
  for (std::size_t s = 0; s < size.size(); ++s)
    if (size[s] > 0) out.best = std::max(out.best, iou(size[s], both[s]));
  std::size_t n = 0, in = 0;
  for (const std::size_t s : chosen) n += size.at(s), in += both.at(s);
  if (n > 0) out.chosen = iou(n, in);
  return out;
}

SegmentRun segment_once(const sim::Frame& f, const io::Config& cfg, const segment::ObjectConfig& object,
                        bool plane, std::uint64_t seed) {
  // The thesis's protocol: no filtering but invalid-value removal (8.2), then optionally RANSAC.
  cloud::PreprocessConfig pre = cfg.preprocess;
  pre.range.enabled = false;
  pre.outliers.enabled = false;
  pre.voxel.enabled = false;
  pre.plane.enabled = plane;
  const segment::Scene sc = segment::segment_scene(f.cloud, pre, cfg.segment, seed);
  SegmentRun r;
  r.finite_ms = sc.timer.ms("finite");
  r.plane_ms = sc.timer.ms("plane");
  r.normals_ms = sc.timer.ms("normals");
  r.region_ms = sc.timer.ms("segment");
  r.points = sc.pre.cloud.size();
  r.segments = sc.info.size();
  std::vector<std::size_t> chosen;  // empty (IoU 0) when no segment passes the selection
  try {
    if (!sc.info.empty())
      chosen = segment::object_segments(sc.info, segment::select_object(sc.info, object), object);
  } catch (const Error&) {
  }
  const Iou iou = truth_iou(segment::input_labels(sc), f.labels, sim::kLabelFirstObject, chosen);
  r.iou = iou.best;
  r.object_iou = iou.chosen;
  return r;
}

// The hfov that gives the barbell about the thesis's point count at the configured resolution.
double thesis_hfov(const sim::World& world, const Simulation& s, std::uint64_t seed) {
  const sim::Frame f = sim::render_rgbd(world, s.world_from_camera, s.render, seed);
  const auto n = std::count(f.labels.begin(), f.labels.end(), sim::kLabelFirstObject);
  if (n == 0) throw Error("scene barbell: the barbell is not in view");
  const double half = std::atan(std::tan(s.render.camera.hfov / 2) * std::sqrt(double(n) / kThesisObjectPoints));
  return 2 * half;
}

struct TimedCheck {
  std::vector<grasp::Check> checks;
  double ms = 0;
};

TimedCheck fast_check(const std::vector<Eigen::Vector3f>& pts, const grasp::Gripper& g,
                      const std::vector<grasp::Candidate>& c) {
  const auto t0 = std::chrono::steady_clock::now();
  const grasp::PointBvh bvh = grasp::build_bvh(pts);  // part of the cost
  TimedCheck out{grasp::check_candidates(bvh, g, c), 0};
  out.ms = ms_since(t0);
  return out;
}

// The thesis's method: every point against every candidate's boxes. Returns ms; `agree` becomes
// false if any candidate's feasibility differs from `fast`.
double brute_check(const std::vector<Eigen::Vector3f>& pts, const grasp::Gripper& g,
                   const std::vector<grasp::Candidate>& c, const std::vector<grasp::Check>& fast,
                   bool& agree) {
  std::vector<char> same(c.size(), 1);
  const auto t0 = std::chrono::steady_clock::now();
  tbb::parallel_for(std::size_t(0), c.size(), [&](std::size_t i) {
    same[i] = grasp::check_brute(pts, g, c[i]).feasible() == fast[i].feasible();
  });
  const double ms = ms_since(t0);
  agree = agree && std::all_of(same.begin(), same.end(), [](char v) { return v != 0; });
  return ms;
}

CheckRun check_once(const sim::Frame& f, const Simulation& s, const ExperimentPlan& plan,
                    std::uint64_t seed, bool brute) {
  io::Config oc = object_config(s, f, 0, plan.sets, seed);
  oc.preprocess.voxel.enabled = false;
  const segment::Scene sc = segment::segment_scene(f.cloud, oc.preprocess, oc.segment, seed);
  std::size_t selected = 0;
  const Cloud full = grasp::object_points(sc, oc.segment.object, selected);
  CheckRun r;
  auto t0 = std::chrono::steady_clock::now();
  const Cloud voxels = cloud::voxel_grid(full, cloud::VoxelConfig{true, 0.0025f, 1}).cloud;
  r.voxel_ms = ms_since(t0);
  const grasp::Frames frames = grasp::make_frames(oc.grasp.frames);
  const auto lf = grasp::points_to_level(full.points, frames);
  const auto lv = grasp::points_to_level(voxels.points, frames);
  const grasp::Gripper g = grasp::make_gripper(oc.grasp.gripper);
  const auto cand = grasp::sample_normal(lf, oc.grasp.sampler, frames.body_from_gripper.linear(), seed, 3000);
  const TimedCheck a = fast_check(lf, g, cand), b = fast_check(lv, g, cand);
  r.full_points = full.size();
  r.voxel_points = voxels.size();
  r.check_full_ms = a.ms;
  r.check_voxel_ms = b.ms;
  r.feasible_full = grasp::count_rejections(a.checks)[0];
  r.feasible_voxel = grasp::count_rejections(b.checks)[0];
  if (brute) {
    r.brute_full_ms = brute_check(lf, g, cand, a.checks, r.agree);
    r.brute_voxel_ms = brute_check(lv, g, cand, b.checks, r.agree);
  }
  return r;
}
}  // namespace

SegmentStudy run_segmentation_study(const ExperimentPlan& plan, const Condition& c) {
  const Simulation s = barbell_simulation(plan, c);
  const sim::World world(s.scene);
  // The object as the barbell preset selects it: the reddest segment and its neighbours (7.4.2).
  const segment::ObjectConfig object =
      io::load_config(preset_path("thesis_barbell.yaml"), plan.sets).segment.object;
  SegmentStudy out;
  for (int i = 0; i < plan.short_iterations; ++i) {
    experiment_step(c, "tables 8.1/8.2", i, plan.short_iterations);
    const std::uint64_t seed = plan.base.seed + static_cast<std::uint64_t>(i);
    const sim::Frame f = sim::render_rgbd(world, s.world_from_camera, s.render, seed);
    out.without_plane.push_back(segment_once(f, plan.base, object, false, seed));
    out.with_plane.push_back(segment_once(f, plan.base, object, true, seed));
  }
  return out;
}

CheckStudy run_check_study(const ExperimentPlan& plan, const Condition& c) {
  Simulation s = barbell_simulation(plan, c);
  const sim::World world(s.scene);
  CheckStudy out;
  out.hfov = thesis_hfov(world, s, plan.base.seed);
  s.render.camera.hfov = out.hfov;
  for (int i = 0; i < plan.short_iterations; ++i) {
    experiment_step(c, "table 8.4", i, plan.short_iterations);
    const std::uint64_t seed = plan.base.seed + static_cast<std::uint64_t>(i);
    const sim::Frame f = sim::render_rgbd(world, s.world_from_camera, s.render, seed);
    out.runs.push_back(check_once(f, s, plan, seed, i < plan.brute_iterations));
  }
  return out;
}

}  // namespace uwgrasp::experiments
