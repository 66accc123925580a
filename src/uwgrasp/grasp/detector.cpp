#include "uwgrasp/grasp/detector.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <numeric>
#include <optional>
#include <cmath>
#include <exception>
#include <functional>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/drawing.hpp"
#include "uwgrasp/grasp/gate.hpp"
#include "uwgrasp/grasp/robust.hpp"

namespace uwgrasp::grasp {

namespace {
LevelCloud to_level(const Cloud& object, const Frames& f) {
  return {points_to_level(object.points, f), directions_to_level(object.normals, f)};
}

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

// The object's visible points and, with the shape on, its unseen surface; and the gripper the
// check uses: grown by the margin the surface's noise asks for.
struct Model {
  LevelCloud cloud;
  Gripper gripper;
  std::optional<Eigen::Vector4f> floor;  // L, from the surroundings' seafloor plane
  LevelCloud core;  // the visible points and the shape's thin core (empty with the shape off)
};
Model object_model(const LevelCloud& l, const Cloud& object, const Gripper& g,
                   const GraspConfig& cfg, const Surroundings* around, ObjectGrasps& out,
                   ShapeTrees trees) {
  Model m{l, g, around ? level_plane(*around, out.frames) : std::nullopt, {}};
  if (!cfg.shape.enabled) return m;
  std::optional<SceneSight> sight;
  if (around != nullptr)
    sight = SceneSight{around->points, around->has_plane ? std::optional(around->plane) : std::nullopt};
  out.shape = complete_shape(l.points, object.points, out.frames, m.floor, cfg.shape, l.normals,
                             sight ? &*sight : nullptr, trees);
  const auto append = [](LevelCloud& to, const std::vector<Eigen::Vector3f>& p, const std::vector<Eigen::Vector3f>& n) {
    to.points.insert(to.points.end(), p.begin(), p.end());
    to.normals.insert(to.normals.end(), n.begin(), n.end());
  };
  append(m.cloud, out.shape.mirrored_points, out.shape.mirrored_normals);
  append(m.cloud, out.shape.points, out.shape.normals);
  m.core = l;
  append(m.core, out.shape.core_points, out.shape.core_normals);
  m.gripper = grow_solids(g, std::max(cfg.shape.min_margin, cfg.shape.margin_sigmas * out.shape.noise));
  return m;
}

// The shape model and the reach check's hull and obstacles. The obstacles depend on the scene
// alone: they are made beside the shape model, whose serial parts leave a thread free (the
// scene's debris, hierarchy and columns take 1.9 ms on one thread on mOSD_learn17's scene,
// 7.3 ms on the mug's). The hull first: it checks the reach configuration they are made with.
struct Modelled {
  Model model;
  std::vector<Solid> solids;
  Obstacles obstacles;
};
Modelled model_and_obstacles(const LevelCloud& l, const Cloud& object, const Gripper& g,
                             const GraspConfig& cfg, const Surroundings* around,
                             const Surroundings& scene, ObjectGrasps& out, ShapeTrees trees) {
  Modelled m;
  if (cfg.reach.enabled) m.solids = vehicle_solids(g, out.frames, cfg.reach);
  tbb::parallel_invoke([&] { m.model = object_model(l, object, g, cfg, around, out, trees); },
                       [&] {
                         if (cfg.reach.enabled)
                           m.obstacles = make_obstacles(scene, out.frames, cfg.reach);
                       });
  return m;
}

// What robust scoring asks the model: `core_bvh` is over m.core's points (unused without them).
ModelView model_view(const Model& m, const PointBvh& bvh, const PointBvh& core_bvh, std::size_t measured,
                     const ObjectShape& shape, const RobustConfig& cfg) {
  ModelView v{bvh, m.cloud.points, m.cloud.normals, measured, shape, m.gripper, m.floor,
              0.0005f + 2.0f * shape.noise, std::max(0.003f, 2.0f * shape.voxel), nullptr, {}, {},
              cfg.core_friction};
  if (!m.core.points.empty()) v.core_bvh = &core_bvh, v.core_points = m.core.points, v.core_normals = m.core.normals;
  return v;
}

// Whether all[a] ranks before all[b]: the higher total, ties by position.
bool ranks_before(const std::vector<Grasp>& all, std::size_t a, std::size_t b) {
  return all[a].scores.total != all[b].scores.total ? all[a].scores.total > all[b].scores.total : a < b;
}

// The leaders of the first measurement measured again with refine_samples new poses each, their
// robustness the share over all the poses measured; repeated while the best is one measured only
// once (a refined leader that fell gives way to the next, which must be refined in its turn).
void refine_leaders(const ModelView& view, const Pool& pool, std::vector<Grasp>& all,
                    std::span<const std::size_t> measured, const RobustConfig& cfg, std::uint64_t seed) {
  if (cfg.refine == 0 || cfg.refine_samples == 0 || cfg.samples == 0) return;
  std::vector<std::size_t> order(measured.begin(), measured.end());
  std::vector<char> refined(all.size(), 0);
  const auto better = [&](std::size_t a, std::size_t b) { return ranks_before(all, a, b); };
  const float n0 = float(cfg.samples), n1 = float(cfg.refine_samples);
  while (!order.empty()) {
    std::sort(order.begin(), order.end(), better);
    if (refined[order.front()]) return;
    std::vector<std::size_t> next;
    for (std::size_t k = 0; k < order.size() && next.size() < cfg.refine; ++k)
      if (!refined[order[k]]) next.push_back(order[k]);
    std::vector<std::uint32_t> which;
    for (std::size_t k : next) which.push_back(all[k].candidate);
    const std::vector<float> more = robustness(view, pool.candidates, which, cfg, seed, cfg.samples, cfg.refine_samples);
    for (std::size_t j = 0; j < next.size(); ++j) {
      Grasp& g = all[next[j]];
      g.robustness = (g.robustness * n0 + more[j] * n1) / (n0 + n1);
      g.robust_poses = cfg.samples + cfg.refine_samples;
      g.scores.total = robust_total(g);
      refined[next[j]] = 1;
    }
  }
}

// The robust mode's scoring (score.hpp): predicted contacts for every feasible candidate, the
// robustness of the best predicted, then the ranking.
std::vector<Grasp> score_robust(const ModelView& view, const LevelCloud& cloud, Pool& pool,
                                const ObjectGrasps& out, const ScoreConfig& cfg, std::uint64_t seed,
                                StageTimer& timer) {
  std::vector<ContactPrediction> predicted(pool.candidates.size());
  tbb::parallel_for(std::size_t(0), pool.candidates.size(), [&](std::size_t i) {
    if (pool.checks[i].feasible()) predicted[i] = predict(view, pool.candidates[i]);
  });
  std::vector<Grasp> all = score_all(cloud.points, cloud.normals, pool.candidates, pool.checks,
                                     out.frames, cfg, out.max_inliers, predicted);
  timer.start("robust");
  std::vector<std::size_t> order(all.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  const std::size_t m = std::min<std::size_t>(cfg.robust.candidates, order.size());
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(m), order.end(),
                    [&](std::size_t a, std::size_t b) { return ranks_before(all, a, b); });
  std::vector<std::uint32_t> which;
  for (std::size_t k = 0; k < m; ++k) which.push_back(all[order[k]].candidate);
  const std::vector<float> share = robustness(view, pool.candidates, which, cfg.robust, seed);
  for (std::size_t k = 0; k < m; ++k) {
    Grasp& g = all[order[k]];
    g.robustness = share[k];
    g.robust_poses = cfg.robust.samples;
    g.scores.total = robust_total(g);
  }
  refine_leaders(view, pool, all, std::span(order.data(), m), cfg.robust, seed);
  // A grasp that holds on the model in none, or too few, of its perturbed poses is not offered
  // (not_robust): "no grasp" is the honest answer when nothing the model shows can be held (e.g.
  // a flat box on the seafloor), not a grasp the detector itself expects to fail. The candidates
  // past the robust.candidates best-predicted are not measured: still feasible, but not offered.
  const auto weak = [&](const Grasp& g) {
    return g.robustness <= 0.0 || g.robustness < cfg.robust.min_robustness;
  };
  for (std::size_t k = 0; k < m; ++k)
    if (weak(all[order[k]])) pool.checks[all[order[k]].candidate].reason = Reject::not_robust;
  std::erase_if(all, weak);
  rank(all, cfg.top);
  return all;
}

// find_grasps' input and settings, checked before any work; the gripper they make.
Gripper check_inputs(const Cloud& object, const GraspConfig& cfg) {
  if (object.size() < 3)
    throw Error("object has " + std::to_string(object.size()) +
                " points; grasp detection needs at least 3");
  if (!object.has_normals()) throw Error("object cloud has no normals; grasp scoring needs them");
  check_consistent(object, "object cloud");
  for (std::size_t i = 0; i < object.size(); ++i)
    if (!is_finite(object.points[i])) throw Error("object point " + std::to_string(i) + " is not finite");
  Gripper g = make_gripper(cfg.gripper);
  check_sampler(cfg.sampler);
  check_weights(cfg.score.weights);
  // Robust mode offers only the grasps it measured: with no pose or no candidate measured every
  // detection would answer "no feasible grasp", however many passed the checks.
  if (cfg.score.mode == ScoreMode::robust &&
      (cfg.score.robust.samples == 0 || cfg.score.robust.candidates == 0))
    throw Error(
        "grasp.score.robust.samples and .candidates must be at least 1 in robust mode "
        "(grasp.score.mode=thesis ranks without measuring)");
  if (cfg.score.weights.vehicle > 0.0 && !cfg.score.hold_cost)
    throw Error("grasp.score.weights.vehicle > 0 needs a vehicle model for the hold cost");
  (void)orientation_score(Eigen::Vector3d::Zero(), cfg.score.orientation);  // validates weights
  return g;
}

// One k-d tree over the object in L for the median spacing and the symmetry planes' alignment
// (each built its own: 1.3 ms a tree on a mOSD object, 4 ms on the mug frame's), and the
// shape's over its camera points for the surface noise: nanoflann builds a tree on one thread,
// so the two are built side by side.
struct Trees {
  std::optional<cloud::KdTree> level, camera;
  ShapeTrees shape() const { return {level ? &*level : nullptr, camera ? &*camera : nullptr}; }
};
void build_trees(const LevelCloud& l, const Cloud& object, const GraspConfig& cfg, double leaf,
                 const Surroundings* around, Trees& t) {
  const bool spacing = cfg.score.inlier_mode != InlierMode::fixed && !(leaf > 0.0);
  tbb::parallel_invoke(
      [&] {
        if (spacing || (cfg.shape.enabled && cfg.shape.symmetry.enabled && around != nullptr))
          t.level.emplace(l.points);
      },
      [&] {
        if (cfg.shape.enabled) t.camera.emplace(object.points);
      });
}
}  // namespace

ObjectGrasps find_grasps(const Cloud& object, const GraspConfig& cfg, double leaf,
                         std::uint64_t seed, StageTimer& timer, const Surroundings* around) {
  const Gripper g = check_inputs(object, cfg);
  ObjectGrasps out;
  out.frames = make_frames(cfg.frames);
  const LevelCloud l = to_level(object, out.frames);
  Trees t;
  build_trees(l, object, cfg, leaf, around, t);
  out.max_inliers = max_inliers(cfg.score, g, l.points, leaf, t.level ? &*t.level : nullptr);
  timer.start("sample");  // first, so the stages print in pipeline order
  timer.start("shape");
  const Surroundings scene = around ? *around : Surroundings{object.points};
  Modelled m = model_and_obstacles(l, object, g, cfg, around, scene, out, t.shape());
  const Model& model = m.model;
  timer.start("check");   // the hierarchy (and the occlusion map beside it) is part of the check's cost
  Shadow shadow;
  const PointBvh bvh = build_inputs(model.cloud, object, model.gripper, cfg.occlusion, shadow);
  Pool pool;
  out.sampler = cfg.sampler.kind;
  const Gate gate({bvh, model.gripper, g, out.shape, out.frames,
                   cfg.occlusion.enabled ? &shadow : nullptr, cfg.occlusion, cfg.reach, scene},
                  std::move(m.solids), std::move(m.obstacles));
  const SampleInputs inputs{l, model.cloud, out.shape, model.gripper, gate, model.floor};
  if (cfg.sampler.kind == SamplerKind::automatic)
    out.sampler = run_auto(inputs, cfg, out.frames, bvh, seed, timer, pool);
  else
    pool.add(draw_checked(cfg.sampler.kind, inputs, cfg, out.frames, bvh, seed, cfg.sampler.samples, 0, timer));
  timer.start("reach");  // with the shape and the shadow
  tbb::parallel_for(std::size_t(0), pool.candidates.size(), [&](std::size_t i) {
    // A candidate that passed the gate while sampling passed these very checks.
    if (pool.checks[i].feasible() && !pool.gated[i]) pool.checks[i].reason = gate.after_check(pool.candidates[i]);
  });
  timer.start("score");
  if (cfg.score.mode == ScoreMode::thesis) {
    out.grasps = score_and_rank(model.cloud.points, model.cloud.normals, pool.candidates, pool.checks,
                                out.frames, cfg.score, out.max_inliers);
  } else {
    const PointBvh core_bvh = model.core.points.empty() ? PointBvh{} : build_bvh(model.core.points);
    ModelView view = model_view(model, bvh, core_bvh, l.points.size(), out.shape, cfg.score.robust);
    if (cfg.score.robust.scene) view.scene = &gate;
    out.grasps = score_robust(view, model.cloud, pool, out, cfg.score, seed, timer);
  }
  timer.stop();
  out.candidates = pool.candidates.size();
  out.rejections = count_rejections(pool.checks);
  return out;
}

}  // namespace uwgrasp::grasp
