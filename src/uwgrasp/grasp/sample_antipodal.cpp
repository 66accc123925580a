// The antipodal sampler (samplers.hpp) on the object's model (shape.hpp).
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/grasp/samplers.hpp"
#include "uwgrasp/grasp/shape.hpp"

namespace uwgrasp::grasp {

namespace {
constexpr std::uint64_t kAntipodal = 5ULL << 40;
constexpr std::uint64_t kLiftStream = 0x9E3779B97F4A7C15ULL;
using V3 = Eigen::Vector3f;

// The grid's faces in L and a line direction's reciprocals, once per back_off: its 15 lines share
// both (dividing per line cost 0.6 of the mug frame's 24 ms sample stage). A product by the
// reciprocal rounds a little differently from the quotient; the step either side covers it.
struct GridSlabs {
  V3 lo, hi, inverse;
  GridSlabs(const ObjectShape& shape, const V3& d)
      : lo(shape.origin - V3::Constant(0.5f * shape.voxel)),
        hi(lo + shape.voxel * V3(float(shape.nx), float(shape.ny), float(shape.nz))),
        inverse(d.cwiseInverse()) {}
};

// The steps i in [first, last] whose points base + i d can lie in the shape's grid (outside
// it every point is free), widened by a step either side against rounding: a palm line's scan
// skips the part of it outside the grid with the same answer (sample stage 52-78 -> 49-65 ms
// on bench/frame's frames).
struct StepRange {
  int first, last;
};
StepRange steps_in_grid(const GridSlabs& g, const V3& base, const V3& d, int first, int last) {
  float t0 = float(first), t1 = float(last);
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12f) {
      if (base[k] < g.lo[k] || base[k] > g.hi[k]) return {1, 0};
      continue;
    }
    const float a = (g.lo[k] - base[k]) * g.inverse[k], b = (g.hi[k] - base[k]) * g.inverse[k];
    t0 = std::max(t0, std::min(a, b)), t1 = std::min(t1, std::max(a, b));
  }
  if (t0 > t1 + 2.0f) return {1, 0};
  return {std::max(first, int(std::floor(t0)) - 1), std::min(last, int(std::ceil(t1)) + 1)};
}

// How far the gripper must back off along -x from `centre` so that its palm face (at
// -palm_offset, `half_width` across y, `half_height` across z) clears the model by a voxel and
// a half (the grid's own quantisation): the furthest the model reaches towards it over a 5 x 3
// grid of lines through the palm's face.
float back_off(const ObjectShape& shape, const V3& centre, const V3& x, const V3& y, float palm_offset,
               float half_width, float half_height) {
  const V3 z = x.cross(y);
  const float step = 0.5f * shape.voxel;
  const int steps = int(2.0f * palm_offset / step);
  int reach = -1;  // in steps; each line is scanned from the far end down to the reach so far
  // The centre line first, the corners last: the reach is the furthest over all lines whatever
  // their order, and a line through the object's middle usually reaches furthest, so the others
  // scan less (voxel lookups 2.8x fewer on mOSD_learn0, 3.6x on the mug, where back_off was
  // half the sample stage's work).
  const V3 d = -step * x;
  const GridSlabs slabs(shape, d);
  for (const float a : {0.0f, -0.5f, 0.5f, -1.0f, 1.0f})
    for (const float b : {0.0f, -1.0f, 1.0f}) {
      const V3 base = centre + a * half_width * y + b * half_height * z;
      const StepRange r = steps_in_grid(slabs, base, d, reach + 1, steps);
      const int hit = last_occupied(shape, base, x, step, r.first, r.last);
      if (hit >= r.first) reach = hit;
    }
  if (reach < 0) return 0.0f;
  return std::max(0.0f, float(reach) * step + 1.5f * shape.voxel - palm_offset);
}

Candidate oriented(const V3& position, const V3& x, const V3& y, std::uint32_t source) {
  Candidate c;
  c.position = position;
  c.rotation.col(0) = x, c.rotation.col(1) = y, c.rotation.col(2) = x.cross(y);
  c.source = static_cast<std::int32_t>(source);
  return c;
}

V3 tilted(const V3& axis, Rng& rng, double sigma) {
  const Eigen::Vector3d w(rng.normal(0.0, sigma), rng.normal(0.0, sigma), rng.normal(0.0, sigma));
  const Eigen::Vector3d a = axis.cast<double>();
  const Eigen::Vector3d w_perp = w - w.dot(a) * a;  // a turn about an axis across `axis`
  if (w_perp.norm() < 1e-12) return axis;
  return (Eigen::AngleAxisd(w_perp.norm(), w_perp.normalized()) * a).cast<float>().normalized();
}

// One candidate: the drawn point's closing axis, approach and turns (see samplers.hpp); whether
// it passed `clear` (with one).
struct Draw {
  std::span<const V3> points, normals;
  const ObjectShape& shape;
  const SamplerConfig& cfg;
  const Eigen::Matrix3d& R_BG;
  float max_width, palm_offset, palm_half_width, palm_half_height;
  const std::vector<std::uint32_t>& eligible;
  const std::vector<std::uint32_t>& focus;  // eligible points near earlier blocks' passes
  const double& focus_share;                 // the share of draws that start from them
  const ClearFn& clear;
  const LiftFn& lift;
  std::uint64_t seed;
  std::uint32_t first;

  // `tries` counts the calls of `clear`; `slot` is the candidate's index in the output.
  bool operator()(Rng& rng, Candidate& c, std::uint32_t slot, std::uint32_t& tries) const {
    const float gap = 2.0f * shape.voxel;
    bool passed = false;
    const int draws = 8;
    for (int attempt = 0; attempt < draws; ++attempt) {
      const bool near_pass = !focus.empty() && rng.uniform() < focus_share;
      const std::uint32_t j =
          near_pass ? focus[rng.below(focus.size())] : eligible[rng.below(eligible.size())];
      const V3 n = normals[j];
      if (!(n.norm() > 0.5f)) continue;
      const V3 y = tilted(-n.normalized(), rng, cfg.sigma_tilt);  // from the near pad into the object
      const float width = extent_along(shape, points[j], y, max_width, gap);
      const V3 x = approach(rng, y);
      if (x.isZero()) continue;
      // The share of the floor clearance this draw keeps, from a stream of its own: where the
      // floor is far, the draws are those drawn without it.
      const std::uint64_t stream = (std::uint64_t(first + slot) << 3) | std::uint64_t(attempt);
      const float lift_to = lift ? float(Rng(seed ^ kLiftStream, stream).uniform()) : 1.0f;
      passed = turn(points[j] + 0.5f * width * y, x, y, j, lift_to, c, slot, tries);
      if (clear ? passed : width <= max_width) break;
    }
    return passed;
  }

  // The gripper's approach at a drawn vehicle attitude, turned across the closing axis y; zero
  // when the two are (nearly) parallel.
  V3 approach(Rng& rng, const V3& y) const {
    const Eigen::Vector3d rpy(rng.normal(0.0, cfg.sigma_theta.x()), rng.normal(0.0, cfg.sigma_theta.y()),
                              rng.normal(0.0, cfg.sigma_theta.z()));
    const V3 a = (quat_from_rpy(rpy).toRotationMatrix() * R_BG).col(0).cast<float>();
    V3 x = a - a.dot(y) * y;
    // Closing along the drawn approach leaves the approach's small remainder across it: the
    // turns make any of its directions usable.
    if (x.norm() < 1e-4f) return V3::Zero();
    x.normalize();
    // An approach climbing more than 20 degrees comes from below the object: mirrored, it
    // comes from above, where a vehicle over the seafloor can be (L's z is down).
    return x.z() < -0.34f ? V3(-x) : x;
  }

  // Of the approach x and its turns about the closing axis by multiples of 360 / turns degrees
  // (nearest first, none from below), the first that passes `clear` (without one: whose palm
  // clears the model within half a finger's back-off); else the one that backs off least. Backed
  // off along its approach until the palm clears.
  bool turn(const V3& mid, const V3& x, const V3& y, std::uint32_t j, float lift_to, Candidate& c,
            std::uint32_t slot, std::uint32_t& tries) const {
    float best_off = std::numeric_limits<float>::max();
    const int turns = int(cfg.turns);
    // Lifted off the floor only when no turn passes as drawn (see SamplerConfig::floor_clearance).
    for (int lifted = 0; lifted < (lift && clear ? 2 : 1); ++lifted)
      for (int t = 0; t < turns; ++t) {
        const int side = (t + 1) / 2 * (t % 2 ? 1 : -1);  // 0, +1, -1, +2, -2, ... steps
        const V3 xt = Eigen::AngleAxisf(float(side) * 2.0f * float(std::numbers::pi) / float(turns), y) * x;
        if (xt.z() < -0.34f) continue;
        const float off = back_off(shape, mid, xt, y, palm_offset, palm_half_width, palm_half_height);
        Candidate k = oriented(mid - off * xt, xt, y, j);
        if (lifted) {
          const float up = lift(k, lift_to);
          if (!(up > 0.0f)) continue;  // the same candidate as drawn: tried
          k.position -= up * xt;
        }
        const bool passed = clear ? (++tries, bool(clear(k, slot))) : off <= 0.5f * palm_offset;
        if (passed || (!lifted && off < best_off)) best_off = off, c = k;
        if (passed) return true;
      }
    return false;
  }
};

// The points worth drawing: a usable normal, and the model no wider than the gripper's usable
// aperture along it (on an object mostly wider than the gripper, the few graspable places);
// every point when none is.
std::vector<std::uint32_t> eligible_points(std::span<const V3> points, std::span<const V3> normals,
                                           const ObjectShape& shape, float max_width) {
  std::vector<char> ok(points.size(), 0);
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t j) {
    ok[j] = normals[j].norm() > 0.5f &&
            extent_along(shape, points[j], -normals[j].normalized(), max_width, 2.0f * shape.voxel) <= max_width;
  });
  std::vector<std::uint32_t> eligible;
  eligible.reserve(points.size());
  for (std::uint32_t j = 0; j < points.size(); ++j)
    if (ok[j]) eligible.push_back(j);
  if (eligible.empty()) {
    eligible.resize(points.size());
    std::iota(eligible.begin(), eligible.end(), 0u);
  }
  return eligible;
}
// Adaptive drawing (after the cross-entropy method): where an object is graspable in a few places
// only (a lying bottle's neck; its body is wider than the gripper), most uniform draws fail every
// check. When fewer than half of the first block's (uniform) candidates pass, a share of each
// later block's draws - the share of the first block that failed - start from the eligible
// points near the drawn points of the passes so far, the rest from anywhere, so that no place is
// given up on. Where uniform draws keep half, they go on alone: focusing there changed the top-1s
// of well-graspable objects without making them better (judged, 2 x 20 seeds: 1,998 of 2,160
// held uniform, 1,987 focused everywhere). The pool grows only between blocks, in candidate
// order: the same seed gives the same candidates on any number of threads.
struct Focus {
  static constexpr std::size_t kNear = 24;  // pool points per pass: ~5 mm on a 2 mm cloud
  std::span<const V3> points;
  // Built at the first pass to add, not with the focus: where nothing passes (the mug of the
  // real stereo frame: 1,024 draws) it was 4.8 ms of a serial build never searched.
  std::optional<cloud::KdTree> tree;
  std::vector<char> is_eligible;

  Focus(std::span<const V3> pts, std::span<const std::uint32_t> eligible)
      : points(pts), is_eligible(pts.size(), 0) {
    for (const std::uint32_t j : eligible) is_eligible[j] = 1;
  }
  void add(const V3& p, std::vector<std::uint32_t>& pool) {
    if (!tree) tree.emplace(points);
    std::uint32_t idx[kNear];
    float d2[kNear];
    const std::size_t n = tree->knn(p, kNear, idx, d2);
    for (std::size_t i = 0; i < n; ++i)
      if (is_eligible[idx[i]]) pool.push_back(idx[i]);
  }
};
}  // namespace

std::vector<Candidate> sample_antipodal(std::span<const Eigen::Vector3f> points,
                                        std::span<const Eigen::Vector3f> normals,
                                        const ObjectShape& shape, const SamplerConfig& cfg,
                                        const Eigen::Matrix3d& R_BG, float max_width,
                                        float palm_offset, float palm_half_width,
                                        float palm_half_height, std::uint64_t seed,
                                        std::uint32_t count, std::uint32_t first,
                                        const ClearFn& clear,
                                        std::uint32_t enough, std::vector<char>* passed_out,
                                        const LiftFn& lift) {
  if (points.empty()) throw Error("antipodal sampler: the object cloud is empty");
  if (normals.size() != points.size()) throw Error("antipodal sampler: the object has no normals");
  if (shape.empty()) throw Error("antipodal sampler: needs the object's shape (grasp.shape.enabled)");
  const std::vector<std::uint32_t> eligible = eligible_points(points, normals, shape, max_width);
  std::optional<Focus> focus;  // made after the first block, when it is needed
  std::vector<std::uint32_t> pool;  // eligible points near the passes of the blocks drawn
  double focus_share = 0.0;
  const Draw draw{points, normals, shape, cfg, R_BG, max_width, palm_offset, palm_half_width,
                  palm_half_height, eligible, pool, focus_share, clear, lift, seed, first};
  // In blocks of a fixed size, so that where an early stop falls depends on the seed alone.
  // Stops once `enough` passed, or once the checks were tried kTries times per candidate on
  // average: on a view where little can pass (a fragment in turbid water) every candidate
  // would otherwise try all its draws' turns (8 x turns checks each), seconds for 3000 (a median 2.7 s
  // per turbid frame; 0.1-0.3 s with the cap). Judged, 5 seeds: a cap of 6 cost coastal water
  // 89 -> 84 % top-1, 16 about 89 -> 86 %.
  constexpr std::uint32_t kBlock = 256;
  constexpr std::uint64_t kTries = 16;
  std::vector<Candidate> out(count);
  std::vector<char> passed(count, 0);
  std::vector<std::uint32_t> tries(count, 0);
  std::uint32_t done = 0, pass = 0;
  std::uint64_t tried = 0;
  while (done < count && !(clear && (pass >= enough || tried >= kTries * count))) {
    const std::uint32_t end = std::min(count, done + kBlock);
    tbb::parallel_for(done, end, [&](std::uint32_t k) {
      Rng rng(seed, kAntipodal + first + k);
      passed[k] = draw(rng, out[k], k, tries[k]);
    });
    pass += std::uint32_t(std::count(passed.begin() + done, passed.begin() + end, 1));
    // Where uniform draws keep half of the first block, they go on alone (see Focus).
    if (clear && cfg.focus && done == 0 && 2 * pass < end) {
      focus.emplace(points, eligible);
      focus_share = 1.0 - double(pass) / double(end);
    }
    if (focus) {
      for (std::uint32_t k = done; k < end; ++k)
        if (passed[k]) focus->add(points[std::uint32_t(out[k].source)], pool);
    }
    tried += std::accumulate(tries.begin() + done, tries.begin() + end, std::uint64_t(0));
    done = end;
  }
  out.resize(done);
  if (passed_out) *passed_out = clear ? std::vector<char>(passed.begin(), passed.begin() + done)
                                      : std::vector<char>(done, 0);
  return out;
}

}  // namespace uwgrasp::grasp
