#include "uwgrasp/grasp/detector.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::grasp {

namespace {
struct LevelCloud {
  std::vector<Eigen::Vector3f> points, normals;
};

LevelCloud to_level(const Cloud& object, const Frames& f) {
  return {points_to_level(object.points, f), directions_to_level(object.normals, f)};
}

std::vector<Candidate> sample(SamplerKind kind, const LevelCloud& l, const GraspConfig& cfg,
                              const Frames& f, std::uint64_t seed, std::uint32_t count,
                              std::uint32_t first) {
  const Eigen::Matrix3d R_BG = f.body_from_gripper.linear();
  switch (kind) {
    case SamplerKind::uniform: return sample_uniform(l.points, cfg.sampler, R_BG, seed, count, first);
    case SamplerKind::surface: return sample_surface(l.points, l.normals, cfg.sampler, seed, count, first);
    default: return sample_normal(l.points, cfg.sampler, R_BG, seed, count, first);
  }
}

// Median distance to the nearest neighbour: the cloud's own "voxel size" when none was set.
double median_spacing(const std::vector<Eigen::Vector3f>& pts) {
  const cloud::KdTree tree(pts);
  const cloud::Neighbours nb = cloud::knn_all(tree, pts, 2);
  std::vector<float> d;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (nb.count[i] > 1) d.push_back(std::sqrt(nb.dists_of(i)[1]));
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

double max_inliers(const ScoreConfig& s, const Gripper& g, const LevelCloud& l, double leaf) {
  if (s.inlier_mode == InlierMode::fixed) return s.max_inliers;
  if (!(leaf > 0.0)) leaf = median_spacing(l.points);
  if (!(leaf > 0.0)) throw Error("derived maximum inliers: the object's points all coincide");
  const Eigen::Vector3f size = g.closing.hi - g.closing.lo;
  return s.inlier_mode == InlierMode::volume ? max_inliers_volume(size, leaf)
                                             : max_inliers_surface(size, leaf);
}

struct Pool {
  std::vector<Candidate> candidates;
  std::vector<Check> checks;
  void add(std::vector<Candidate> c, std::vector<Check> k) {
    candidates.insert(candidates.end(), c.begin(), c.end());
    std::move(k.begin(), k.end(), std::back_inserter(checks));
  }
};

// The object's depth map and the gripper's part samples for the occlusion check.
struct Shadow {
  DepthMap map;
  PartSamples samples;
};

// Runs f, keeping what it throws for the caller to raise.
template <class F>
void capture(F&& f, std::exception_ptr& error) {
  try {
    f();
  } catch (...) {
    error = std::current_exception();
  }
}

// The point BVH and, when the occlusion check is on, its inputs, built side by side: the BVH
// of a small object is built mostly on one thread, so the map takes the other core (0.1 ms of
// a 5.8k-point object's 2 ms, 0.7 ms of a 65k-point one's 8). Errors are raised in a fixed
// order, the BVH's first, whichever thread hit its own first.
PointBvh build_inputs(const LevelCloud& l, const Cloud& object, const Gripper& g,
                      const OcclusionConfig& cfg, Shadow& shadow) {
  PointBvh bvh;
  std::exception_ptr bvh_error, shadow_error;
  const auto make_shadow = [&] {
    if (cfg.enabled)
      shadow = {make_depth_map(object.points, cfg.resolution), part_samples(g, cfg.spacing)};
  };
  tbb::parallel_invoke([&] { capture([&] { bvh = build_bvh(l.points); }, bvh_error); },
                       [&] { capture(make_shadow, shadow_error); });
  for (const std::exception_ptr& e : {bvh_error, shadow_error})
    if (e) std::rethrow_exception(e);
  return bvh;
}

// Feasible candidates with a solid part in the object's shadow become `occluded`.
void reject_occluded(const Shadow& shadow, const Frames& f, const OcclusionConfig& cfg, Pool& pool) {
  const DepthMap& map = shadow.map;
  const PartSamples& samples = shadow.samples;
  const Pose camera_from_level = f.level_from_camera.inverse();
  tbb::parallel_for(std::size_t(0), pool.candidates.size(), [&](std::size_t i) {
    if (pool.checks[i].feasible() &&
        occluded(map, samples, pool.candidates[i], camera_from_level, cfg))
      pool.checks[i].reason = Reject::occluded;
  });
}

// Feasible candidates the whole vehicle cannot take (reach.hpp).
void reject_unreachable(const Cloud& object, const Surroundings* around, const Gripper& g,
                        const Frames& f, const ReachConfig& cfg, Pool& pool) {
  const std::vector<Solid> solids = vehicle_solids(g, f, cfg);
  const Surroundings fallback{object.points};
  const Obstacles o = make_obstacles(around ? *around : fallback, f);
  tbb::parallel_for(std::size_t(0), pool.candidates.size(), [&](std::size_t i) {
    if (pool.checks[i].feasible()) pool.checks[i].reason = reach_check(o, solids, pool.candidates[i], cfg);
  });
}

// automatic: a pilot share on each sampler, then the rest of the budget on the one that found
// the most feasible candidates (ties: normal, uniform, surface - the thesis's order of use).
SamplerKind run_auto(const LevelCloud& l, const GraspConfig& cfg, const Frames& f,
                     const Gripper& g, const PointBvh& bvh, std::uint64_t seed, StageTimer& timer,
                     Pool& pool) {
  const auto n = cfg.sampler.samples;
  const auto pilot = static_cast<std::uint32_t>(std::lround(cfg.sampler.pilot * n));
  SamplerKind best = SamplerKind::normal;
  std::size_t best_feasible = 0;
  for (SamplerKind k : {SamplerKind::normal, SamplerKind::uniform, SamplerKind::surface}) {
    timer.start("sample");
    auto c = sample(k, l, cfg, f, seed, pilot, 0);
    timer.start("check");
    auto checks = check_candidates(bvh, g, c);
    const std::size_t feasible = count_rejections(checks)[0];
    if (feasible > best_feasible) best = k, best_feasible = feasible;
    pool.add(std::move(c), std::move(checks));
  }
  timer.start("sample");
  auto c = sample(best, l, cfg, f, seed, n - std::min(n, 3 * pilot), pilot);
  timer.start("check");
  auto checks = check_candidates(bvh, g, c);
  pool.add(std::move(c), std::move(checks));
  return best;
}
}  // namespace

ObjectGrasps find_grasps(const Cloud& object, const GraspConfig& cfg, double leaf,
                         std::uint64_t seed, StageTimer& timer, const Surroundings* around) {
  if (object.size() < 3)
    throw Error("object has " + std::to_string(object.size()) +
                " points; grasp detection needs at least 3");
  if (!object.has_normals()) throw Error("object cloud has no normals; grasp scoring needs them");
  check_consistent(object, "object cloud");
  const Gripper g = make_gripper(cfg.gripper);
  check_sampler(cfg.sampler);
  check_weights(cfg.score.weights);
  if (cfg.score.weights.vehicle > 0.0 && !cfg.score.hold_cost)
    throw Error("grasp.score.weights.vehicle > 0 needs a vehicle model for the hold cost");
  (void)orientation_score(Eigen::Vector3d::Zero(), cfg.score.orientation);  // validates weights

  ObjectGrasps out;
  out.frames = make_frames(cfg.frames);
  const LevelCloud l = to_level(object, out.frames);
  out.max_inliers = max_inliers(cfg.score, g, l, leaf);
  timer.start("sample");  // first, so the stages print in pipeline order
  timer.start("check");   // the hierarchy (and the occlusion map beside it) is part of the check's cost
  Shadow shadow;
  const PointBvh bvh = build_inputs(l, object, g, cfg.occlusion, shadow);
  Pool pool;
  out.sampler = cfg.sampler.kind;
  if (cfg.sampler.kind == SamplerKind::automatic) {
    out.sampler = run_auto(l, cfg, out.frames, g, bvh, seed, timer, pool);
  } else {
    timer.start("sample");
    auto c = sample(cfg.sampler.kind, l, cfg, out.frames, seed, cfg.sampler.samples, 0);
    timer.start("check");
    auto checks = check_candidates(bvh, g, c);
    pool.add(std::move(c), std::move(checks));
  }
  if (cfg.occlusion.enabled) {
    timer.start("occlusion");
    reject_occluded(shadow, out.frames, cfg.occlusion, pool);
  }
  if (cfg.reach.enabled) {
    timer.start("reach");
    reject_unreachable(object, around, g, out.frames, cfg.reach, pool);
  }
  timer.start("score");
  out.grasps = score_and_rank(l.points, l.normals, pool.candidates, pool.checks, out.frames,
                              cfg.score, out.max_inliers);
  timer.stop();
  out.candidates = pool.candidates.size();
  out.rejections = count_rejections(pool.checks);
  return out;
}

Cloud object_points(const segment::Scene& scene, const segment::ObjectConfig& cfg,
                    std::size_t& selected) {
  if (scene.info.empty()) throw Error("segmentation found no segment to grasp");
  selected = segment::select_object(scene.info, cfg);
  std::vector<std::uint32_t> points;
  for (const std::size_t s : segment::object_segments(scene.info, selected, cfg)) {
    const auto& idx = scene.segmentation.segments[s];
    points.insert(points.end(), idx.begin(), idx.end());
  }
  std::sort(points.begin(), points.end());
  return select(scene.pre.cloud, points);
}

Surroundings surroundings(const segment::Scene& scene) {
  return {scene.pre.cloud.points, scene.pre.plane.found, scene.pre.plane.coefficients};
}

Detection detect(const Cloud& input, const cloud::PreprocessConfig& pre,
                 const segment::SegmentConfig& seg, const GraspConfig& cfg, std::uint64_t seed) {
  Detection d;
  d.scene = segment::segment_scene(input, pre, seg, seed);
  d.timer = d.scene.timer;
  d.timer.start("select");
  d.object = object_points(d.scene, seg.object, d.segment);
  d.timer.stop();
  const double leaf = pre.voxel.enabled ? pre.voxel.leaf : 0.0;
  const Surroundings around = surroundings(d.scene);
  d.result = find_grasps(d.object, cfg, leaf, seed, d.timer, &around);
  return d;
}

Pose camera_from_gripper(const Grasp& g, const Frames& f) {
  return f.level_from_camera.inverse() * g.level_from_gripper;
}

}  // namespace uwgrasp::grasp
