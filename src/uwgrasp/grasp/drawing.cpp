#include "uwgrasp/grasp/drawing.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace uwgrasp::grasp {

namespace {
// How far c must back off along its approach x so that every corner of the gripper's solids is
// `clearance` above the seafloor: a bar lying on it is then held near the fingertips rather than
// drawn with them at the floor, where the smallest error of the vehicle's pose drives them into
// it (the robust share of such grasps was 0). 0 when the gripper is clear, or when backing off
// hardly lifts it (an approach within ~12 degrees of level): the checks then decide.
float floor_lift(const Gripper& g, const Eigen::Vector4f& floor, float clearance, const Candidate& c) {
  const Eigen::Vector3f n = floor.head<3>();
  const float rise = -n.dot(c.rotation.col(0));  // height gained per metre backed off
  if (rise < 0.2f) return 0.0f;
  float lowest = std::numeric_limits<float>::max();
  for (const Box& b : g.solids)
    for (int k = 0; k < 8; ++k) lowest = std::min(lowest, n.dot(c.rotation * b.corner(k) + c.position) + floor[3]);
  return std::max(0.0f, (clearance - lowest) / rise);
}

// Whether the object is lower above the seafloor than the fingers are long (its 99th
// percentile of height, so that a stray point does not decide): then every grasp from above
// that centres the pads on it puts the fingertips at the floor, and the lift is the way to hold
// it. A taller object has grasps clear of the floor as drawn; lifting its draws near the floor
// (a barbell's bar between its plates) gave grasps closing on the bar's edges that the judge
// finds out of force closure and our prediction did not (noisy water).
bool lower_than_fingers(std::span<const Eigen::Vector3f> points, const Eigen::Vector4f& floor, const Gripper& g) {
  if (points.empty()) return false;
  std::vector<float> height(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) height[i] = floor.head<3>().dot(points[i]) + floor[3];
  const auto high = height.begin() + std::ptrdiff_t(99 * (height.size() - 1) / 100);
  std::nth_element(height.begin(), high, height.end());
  return *high < g.config.finger_length;
}

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
      const auto clearance = float(cfg.sampler.floor_clearance);
      LiftFn lift;
      if (in.floor && clearance > 0.0f && lower_than_fingers(in.model.points, *in.floor, in.gripper))
        lift = [&](const Candidate& c, float share) { return floor_lift(in.gripper, *in.floor, share * clearance, c); };
      return sample_antipodal(in.model.points, in.model.normals, in.shape, cfg.sampler, R_BG,
                              max_grasp_width(in.gripper), -palm.hi.x(), palm.half().y(),
                              palm.half().z(), seed, count, first, clear, enough, &d.passed, lift);
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
}  // namespace

Drawn draw_checked(SamplerKind kind, const SampleInputs& in, const GraspConfig& cfg, const Frames& f,
                   const PointBvh& bvh, std::uint64_t seed, std::uint32_t count, std::uint32_t first,
                   StageTimer& timer) {
  timer.start("sample");
  Drawn d = sample(kind, in, cfg, f, seed, count, first);
  timer.start("check");
  check_rest(bvh, in.gripper, d);
  return d;
}

SamplerKind run_auto(const SampleInputs& in, const GraspConfig& cfg, const Frames& f, const PointBvh& bvh,
                     std::uint64_t seed, StageTimer& timer, Pool& pool) {
  const auto n = cfg.sampler.samples;
  const auto pilot = static_cast<std::uint32_t>(std::lround(cfg.sampler.pilot * n));
  std::vector<SamplerKind> kinds{SamplerKind::normal, SamplerKind::uniform, SamplerKind::surface};
  if (!in.shape.empty()) kinds.push_back(SamplerKind::antipodal);
  SamplerKind best = SamplerKind::normal;
  std::size_t best_feasible = 0;
  for (SamplerKind k : kinds) {
    Drawn d = draw_checked(k, in, cfg, f, bvh, seed, pilot, 0, timer);
    std::size_t feasible = 0;
    for (std::size_t i = 0; i < d.candidates.size(); ++i)
      feasible += d.checks[i].feasible() && (d.passed[i] || in.gate.after_check(d.candidates[i]) == Reject::none);
    if (feasible > best_feasible) best = k, best_feasible = feasible;
    pool.add(std::move(d));
  }
  const auto used = std::min<std::uint32_t>(n, std::uint32_t(kinds.size()) * pilot);
  pool.add(draw_checked(best, in, cfg, f, bvh, seed, n - used, pilot, timer));
  return best;
}

}  // namespace uwgrasp::grasp
