#include "uwgrasp/grasp/detector.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <numeric>
#include <cmath>
#include <exception>
#include <functional>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/gate.hpp"
#include "uwgrasp/grasp/robust.hpp"

namespace uwgrasp::grasp {

namespace {
struct LevelCloud {
  std::vector<Eigen::Vector3f> points, normals;
};

LevelCloud to_level(const Cloud& object, const Frames& f) {
  return {points_to_level(object.points, f), directions_to_level(object.normals, f)};
}

// What the samplers draw from: the visible points (L), the object's model (its visible points
// and unseen surface, L) and its shape.
struct SampleInputs {
  const LevelCloud& l;
  const LevelCloud& model;
  const ObjectShape& shape;
  const Gripper& gripper;  // as checked (grown by the margin)
  const Gate& gate;  // every check before scoring
};


// The candidates drawn and, for those that passed every check while drawn (only the antipodal
// sampler checks as it draws), `passed` and their gripper check: those need not be checked again.
struct Drawn {
  std::vector<Candidate> candidates;
  std::vector<char> passed;
  std::vector<Check> checks;
};

std::vector<Candidate> draw(SamplerKind kind, const SampleInputs& in, const GraspConfig& cfg,
                            const Frames& f, std::uint64_t seed, std::uint32_t count,
                            std::uint32_t first, Drawn& d) {
  const Eigen::Matrix3d R_BG = f.body_from_gripper.linear();
  const LevelCloud& l = in.l;
  switch (kind) {
    case SamplerKind::uniform: return sample_uniform(l.points, cfg.sampler, R_BG, seed, count, first);
    case SamplerKind::surface: return sample_surface(l.points, l.normals, cfg.sampler, seed, count, first);
    case SamplerKind::antipodal:
      // Without the object's shape there is no far side to find: the surface sampler instead.
      if (in.shape.empty()) return sample_surface(l.points, l.normals, cfg.sampler, seed, count, first);
    {
      const Box& palm = in.gripper.solids[int(Part::palm)];
      // From every surface the model has, unseen ones included: a bar seen end-on from above
      // shows no side to close on, its model does.
      const std::uint32_t enough = cfg.sampler.enough == 0 ? count : cfg.sampler.enough;
      d.checks.resize(count);
      const ClearFn clear = [&](const Candidate& c, std::uint32_t slot) { return in.gate.passes(c, &d.checks[slot]); };
      return sample_antipodal(in.model.points, in.model.normals, in.shape, cfg.sampler, R_BG,
                              max_grasp_width(in.gripper), -palm.hi.x(), palm.half().y(),
                              palm.half().z(), seed, count, first, clear, enough, &d.passed);
    }
    default: return sample_normal(l.points, cfg.sampler, R_BG, seed, count, first);
  }
}

Drawn sample(SamplerKind kind, const SampleInputs& in, const GraspConfig& cfg, const Frames& f,
             std::uint64_t seed, std::uint32_t count, std::uint32_t first) {
  Drawn d;
  d.candidates = draw(kind, in, cfg, f, seed, count, first, d);
  d.passed.resize(d.candidates.size(), 0);
  d.checks.resize(d.candidates.size());
  return d;
}

// The gripper check of the candidates that did not pass while drawn (the same Checker as the
// gate's: those that passed keep the check the gate made; 10-13 ms a frame saved).
void check_rest(const PointBvh& bvh, const Gripper& g, Drawn& d) {
  const Checker check(bvh, g);
  tbb::parallel_for(std::size_t(0), d.candidates.size(), [&](std::size_t i) {
    if (!d.passed[i]) d.checks[i] = check(d.candidates[i]);
  });
}

struct Pool {
  std::vector<Candidate> candidates;
  std::vector<Check> checks;
  std::vector<char> gated;  // passed every check while sampling
  void add(Drawn d) {
    gated.insert(gated.end(), d.passed.begin(), d.passed.end());
    candidates.insert(candidates.end(), d.candidates.begin(), d.candidates.end());
    checks.insert(checks.end(), d.checks.begin(), d.checks.end());
  }
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

// The object's visible points and, with the shape on, its unseen surface; and the gripper the
// check uses: grown by the margin the surface's noise asks for.
struct Model {
  LevelCloud cloud;
  Gripper gripper;
  std::optional<Eigen::Vector4f> floor;  // L, from the surroundings' seafloor plane
  LevelCloud core;  // the visible points and the shape's thin core (empty with the shape off)
};
Model object_model(const LevelCloud& l, const Cloud& object, const Gripper& g, const GraspConfig& cfg,
                   const Surroundings* around, ObjectGrasps& out) {
  Model m{l, g, around ? level_plane(*around, out.frames) : std::nullopt, {}};
  if (!cfg.shape.enabled) return m;
  std::optional<SceneSight> sight;
  if (around != nullptr)
    sight = SceneSight{around->points, around->has_plane ? std::optional(around->plane) : std::nullopt};
  out.shape = complete_shape(l.points, object.points, out.frames, m.floor, cfg.shape, l.normals,
                             sight ? &*sight : nullptr);
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

// What robust scoring asks the model: `core_bvh` is over m.core's points (unused without them).
ModelView model_view(const Model& m, const PointBvh& bvh, const PointBvh& core_bvh, std::size_t measured,
                     const ObjectShape& shape, const RobustConfig& cfg) {
  ModelView v{bvh, m.cloud.points, m.cloud.normals, measured, shape, m.gripper, m.floor,
              0.0005f + 2.0f * shape.noise, std::max(0.003f, 2.0f * shape.voxel), nullptr, {}, {},
              cfg.core_friction};
  if (!m.core.points.empty()) v.core_bvh = &core_bvh, v.core_points = m.core.points, v.core_normals = m.core.normals;
  return v;
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
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(m), order.end(), [&](std::size_t a, std::size_t b) {
    return all[a].scores.total != all[b].scores.total ? all[a].scores.total > all[b].scores.total : a < b;
  });
  std::vector<std::uint32_t> which;
  for (std::size_t k = 0; k < m; ++k) which.push_back(all[order[k]].candidate);
  const std::vector<float> share = robustness(view, pool.candidates, which, cfg.robust, seed);
  for (std::size_t k = 0; k < m; ++k) {
    Grasp& g = all[order[k]];
    g.robustness = share[k];
    g.scores.total = robust_total(g);
  }
  // A grasp that holds on the model in none of its perturbed poses is not offered (not_robust):
  // "no grasp" is the honest answer when nothing the model shows can be held (e.g. a flat box
  // on the seafloor), not a grasp the detector itself expects to fail. The candidates past the
  // robust.candidates best-predicted are not measured: still feasible, but not offered either.
  for (std::size_t k = 0; k < m; ++k)
    if (all[order[k]].robustness <= 0.0) pool.checks[all[order[k]].candidate].reason = Reject::not_robust;
  std::erase_if(all, [](const Grasp& g) { return g.robustness <= 0.0; });
  rank(all, cfg.top);
  return all;
}

// automatic: a pilot share on each sampler, then the rest of the budget on the one that found
// the most feasible candidates (ties: normal, uniform, surface, antipodal - the thesis's order of
// use, then ours; antipodal only when the object has a shape model to close on).
SamplerKind run_auto(const SampleInputs& in, const GraspConfig& cfg, const Frames& f,
                     const Gripper& g, const PointBvh& bvh, std::uint64_t seed, StageTimer& timer,
                     Pool& pool) {
  const auto n = cfg.sampler.samples;
  const auto pilot = static_cast<std::uint32_t>(std::lround(cfg.sampler.pilot * n));
  std::vector<SamplerKind> kinds{SamplerKind::normal, SamplerKind::uniform, SamplerKind::surface};
  if (!in.shape.empty()) kinds.push_back(SamplerKind::antipodal);
  SamplerKind best = SamplerKind::normal;
  std::size_t best_feasible = 0;
  for (SamplerKind k : kinds) {
    timer.start("sample");
    Drawn d = sample(k, in, cfg, f, seed, pilot, 0);
    timer.start("check");
    check_rest(bvh, g, d);
    std::size_t feasible = 0;
    for (std::size_t i = 0; i < d.candidates.size(); ++i)
      feasible += d.checks[i].feasible() && (d.passed[i] || in.gate.after_check(d.candidates[i]) == Reject::none);
    if (feasible > best_feasible) best = k, best_feasible = feasible;
    pool.add(std::move(d));
  }
  const auto used = std::min<std::uint32_t>(n, std::uint32_t(kinds.size()) * pilot);
  timer.start("sample");
  Drawn d = sample(best, in, cfg, f, seed, n - used, pilot);
  timer.start("check");
  check_rest(bvh, g, d);
  pool.add(std::move(d));
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
  for (std::size_t i = 0; i < object.size(); ++i)
    if (!is_finite(object.points[i])) throw Error("object point " + std::to_string(i) + " is not finite");
  const Gripper g = make_gripper(cfg.gripper);
  check_sampler(cfg.sampler);
  check_weights(cfg.score.weights);
  if (cfg.score.weights.vehicle > 0.0 && !cfg.score.hold_cost)
    throw Error("grasp.score.weights.vehicle > 0 needs a vehicle model for the hold cost");
  (void)orientation_score(Eigen::Vector3d::Zero(), cfg.score.orientation);  // validates weights

  ObjectGrasps out;
  out.frames = make_frames(cfg.frames);
  const LevelCloud l = to_level(object, out.frames);
  out.max_inliers = max_inliers(cfg.score, g, l.points, leaf);
  timer.start("sample");  // first, so the stages print in pipeline order
  timer.start("shape");
  const Model model = object_model(l, object, g, cfg, around, out);
  timer.start("check");   // the hierarchy (and the occlusion map beside it) is part of the check's cost
  Shadow shadow;
  const PointBvh bvh = build_inputs(model.cloud, object, model.gripper, cfg.occlusion, shadow);
  Pool pool;
  out.sampler = cfg.sampler.kind;
  const Surroundings scene = around ? *around : Surroundings{object.points};
  const Gate gate({bvh, model.gripper, g, out.shape, out.frames, cfg.occlusion.enabled ? &shadow : nullptr,
                   cfg.occlusion, cfg.reach, scene});
  const SampleInputs inputs{l, model.cloud, out.shape, model.gripper, gate};
  if (cfg.sampler.kind == SamplerKind::automatic) {
    out.sampler = run_auto(inputs, cfg, out.frames, model.gripper, bvh, seed, timer, pool);
  } else {
    timer.start("sample");
    Drawn d = sample(cfg.sampler.kind, inputs, cfg, out.frames, seed, cfg.sampler.samples, 0);
    timer.start("check");
    check_rest(bvh, model.gripper, d);
    pool.add(std::move(d));
  }
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
    const ModelView view = model_view(model, bvh, core_bvh, l.points.size(), out.shape, cfg.score.robust);
    out.grasps = score_robust(view, model.cloud, pool, out, cfg.score, seed, timer);
  }
  timer.stop();
  out.candidates = pool.candidates.size();
  out.rejections = count_rejections(pool.checks);
  return out;
}

}  // namespace uwgrasp::grasp
