#include "uwgrasp/grasp/feasibility.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <memory>

#include "uwgrasp/grasp/feasibility_closing.hpp"
#include "uwgrasp/grasp/lanes.hpp"

namespace uwgrasp::grasp {

namespace {
using lanes::Box4;
using lanes::M4;
using lanes::V3;
using closing_detail::Closing, closing_detail::collision;

// The gripper's boxes (gripper frame) broadcast to four lanes, once per call.
struct GripperLanes {
  Box4 bounds, closing;
  std::array<Box4, kParts> solids;
  explicit GripperLanes(const Gripper& g)
      : bounds(Box4::splat(g.bounds.lo, g.bounds.hi)), closing(Box4::splat(g.closing.lo, g.closing.hi)) {
    for (std::size_t s = 0; s < kParts; ++s) solids[s] = Box4::splat(g.solids[s].lo, g.solids[s].hi);
  }
};

// A box's world-axis bounds in L as centre and half extents, broadcast.
struct Near4 {
  V3 centre, half;
};

// A candidate's frame: local = Rt * (world - t), with the world-axis bounds of its boxes in L.
// Built only for candidates the probe points let through (the probe needs the map alone): the
// bounds cost 7 % of the check on the voxel barbell when built for every candidate.
struct LocalFrame {
  const lanes::Frame4& to_gripper;
  Near4 bounds, closing;               // the whole gripper, the closing region
  std::array<Near4, kParts> solids{};  // each solid part
};

LocalFrame local_frame(const Gripper& g, const Candidate& c, const lanes::Frame4& to_gripper) {
  const Eigen::Matrix3f abs_r = c.rotation.cwiseAbs();
  const auto near = [&](const Box& b) {
    return Near4{V3::splat(c.rotation * b.centre() + c.position), V3::splat(abs_r * b.half())};
  };
  LocalFrame f{to_gripper, near(g.bounds), near(g.closing), {}};
  for (std::size_t s = 0; s < kParts; ++s) f.solids[s] = near(g.solids[s]);
  return f;
}


// The first of four gripper-frame points in a solid part, then its first part (NaN lanes are
// in none).
Reject first_solid(const GripperLanes& g, const V3& p) {
  const M4 in = lanes::contains(p, g.bounds);
  if (!lanes::bits(in)) return Reject::none;
  std::array<int, kParts> hit{};
  int any = 0;
  for (std::size_t s = 0; s < kParts; ++s) any |= hit[s] = lanes::bits(in & lanes::contains(p, g.solids[s]));
  if (any == 0) return Reject::none;
  const int lane = std::countr_zero(unsigned(any));
  for (std::size_t s = 0; s < kParts; ++s)
    if ((hit[s] >> lane) & 1) return collision(int(s));
  return Reject::none;
}

V3 centres(const BvhNode& n) { return lanes::load(n.cx, n.cy, n.cz); }
V3 halves(const BvhNode& n) { return lanes::load(n.hx, n.hy, n.hz); }

// Points spread evenly along the Morton order (so over the whole object), tested before any
// walk. A colliding candidate holds a median 4 % of a barbell's points in its solid parts; 64
// spread points stop 77 % of the barbell's collisions in 16 four-lane steps, where a walk takes
// about 10 node steps and 3 leaves. Which point stops a candidate depends only on the cloud, not
// on the thread count.
constexpr std::size_t kProbes = 64;

struct Probe {
  alignas(16) float x[kProbes], y[kProbes], z[kProbes];
  explicit Probe(const PointBvh& bvh) {
    const std::size_t n = bvh.points.size();
    for (std::size_t i = 0; i < kProbes; ++i) {
      const Eigen::Vector3f p = i < n ? bvh.points[(2 * i + 1) * n / (2 * kProbes)] : Eigen::Vector3f::Constant(NAN);
      x[i] = p.x(), y[i] = p.y(), z[i] = p.z();
    }
  }
  Reject test(const GripperLanes& g, const lanes::Frame4& to_gripper) const {
    for (std::size_t k = 0; k < kProbes; k += 4)
      if (const Reject r = first_solid(g, to_gripper.point(lanes::load(&x[k], &y[k], &z[k])));
          r != Reject::none)
        return r;
    return Reject::none;
  }
};

struct Walker {
  const PointBvh& bvh;
  const GripperLanes& g;
  const LocalFrame& f;

  // The children's boxes in the gripper frame (conservative), and the children that are near
  // the target along the world axes and overlap it along the gripper axes.
  M4 children(const BvhNode& n, const Box4& target, const Near4& world, Box4& local) const {
    const V3 c = centres(n), h = halves(n);
    const M4 near = lanes::near(c, h, world.centre, world.half);
    if (!lanes::bits(near)) return near;
    local = f.to_gripper.boxes(c, h);
    return near & lanes::overlap(local, target);
  }

  // Phase 1: the first point in a solid part under node j of `level`, if any.
  Reject solids(std::uint32_t level, std::uint32_t j) const {
    const BvhNode& n = bvh.levels[level][j];
    Box4 local;
    const V3 c0 = centres(n), h0 = halves(n);
    const M4 m = lanes::near(c0, h0, f.bounds.centre, f.bounds.half);
    if (!lanes::bits(m)) return Reject::none;
    local = f.to_gripper.boxes(c0, h0);
    M4 touch = {0, 0, 0, 0};
    for (std::size_t s = 0; s < kParts; ++s) {
      const M4 hit = m & lanes::overlap(local, g.solids[s]);
      if (!lanes::bits(hit)) continue;
      // A child wholly inside a part has all its points in it.
      if (lanes::bits(hit & lanes::inside(local, g.solids[s]))) return collision(int(s));
      touch |= hit & lanes::near(c0, h0, f.solids[s].centre, f.solids[s].half);
    }
    for (int t = lanes::bits(touch); t != 0; t &= t - 1) {
      const std::uint32_t child = 4 * j + static_cast<std::uint32_t>(std::countr_zero(unsigned(t)));
      const Reject r = level == 0 ? leaf_solids(child) : solids(level - 1, child);
      if (r != Reject::none) return r;
    }
    return Reject::none;
  }

  V3 leaf_points(std::uint32_t k) const {
    return f.to_gripper.point(lanes::load(&bvh.x[k], &bvh.y[k], &bvh.z[k]));
  }

  Reject leaf_solids(std::uint32_t leaf) const {
    for (std::uint32_t k = leaf * kLeafPoints; k < (leaf + 1) * kLeafPoints; k += 4)
      if (const Reject r = first_solid(g, leaf_points(k)); r != Reject::none) return r;
    return Reject::none;
  }

  // Phase 2: the closing region's statistics (no point is in a solid part any more).
  void closing(std::uint32_t level, std::uint32_t j, Closing& acc) const {
    const BvhNode& n = bvh.levels[level][j];
    Box4 local;
    const M4 m = children(n, g.closing, f.closing, local);
    if (!lanes::bits(m)) return;
    const int in = lanes::bits(m & lanes::inside(local, g.closing));
    for (int t = lanes::bits(m); t != 0; t &= t - 1) {
      const int lane = std::countr_zero(unsigned(t));
      const std::uint32_t child = 4 * j + static_cast<std::uint32_t>(lane);
      if (((in >> lane) & 1) && acc.cannot_improve(local.lo.lane(lane), local.hi.lane(lane)))
        acc.out.inliers += bvh.count(level, j, lane);
      else if (level == 0)
        leaf_closing(child, acc);
      else
        closing(level - 1, child, acc);
    }
  }

  // Every point in the closing region, as indices into the cloud.
  void collect(std::uint32_t level, std::uint32_t j, std::vector<std::uint32_t>& out) const {
    const BvhNode& n = bvh.levels[level][j];
    Box4 local;
    const M4 m = children(n, g.closing, f.closing, local);
    for (int t = lanes::bits(m); t != 0; t &= t - 1) {
      const std::uint32_t child = 4 * j + static_cast<std::uint32_t>(std::countr_zero(unsigned(t)));
      if (level > 0) {
        collect(level - 1, child, out);
        continue;
      }
      for (std::uint32_t k = child * kLeafPoints; k < (child + 1) * kLeafPoints; k += 4) {
        const V3 p = leaf_points(k);
        for (int u = lanes::bits(lanes::contains(p, g.closing)); u != 0; u &= u - 1)
          out.push_back(bvh.index[k + std::uint32_t(std::countr_zero(unsigned(u)))]);
      }
    }
  }

  void leaf_closing(std::uint32_t leaf, Closing& acc) const {
    for (std::uint32_t k = leaf * kLeafPoints; k < (leaf + 1) * kLeafPoints; k += 4) {
      const V3 p = leaf_points(k);
      for (int t = lanes::bits(lanes::contains(p, g.closing)); t != 0; t &= t - 1) {
        const int lane = std::countr_zero(unsigned(t));
        acc.add(p.lane(lane), bvh.index[k + std::uint32_t(lane)]);
      }
    }
  }
};
}  // namespace

struct Checker::State {
  const PointBvh& bvh;
  GripperLanes lanes;
  Probe probe;
};

Checker::Checker(const PointBvh& bvh, const Gripper& g)
    : gripper_(g), state_(std::make_shared<const State>(State{bvh, GripperLanes(g), Probe(bvh)})) {}

Reject Checker::solids(const Candidate& c) const {
  const lanes::Frame4 to_gripper(c.rotation.transpose(), c.position);
  if (const Reject r = state_->probe.test(state_->lanes, to_gripper); r != Reject::none) return r;
  const LocalFrame f = local_frame(gripper_, c, to_gripper);
  return Walker{state_->bvh, state_->lanes, f}.solids(state_->bvh.top(), 0);
}

Check Checker::operator()(const Candidate& c) const {
  Check out;
  const lanes::Frame4 to_gripper(c.rotation.transpose(), c.position);
  out.reason = state_->probe.test(state_->lanes, to_gripper);
  if (out.reason != Reject::none) return out;
  const LocalFrame f = local_frame(gripper_, c, to_gripper);
  const Walker w{state_->bvh, state_->lanes, f};
  out.reason = w.solids(state_->bvh.top(), 0);
  if (out.reason != Reject::none) return out;
  Closing acc{out};
  w.closing(state_->bvh.top(), 0, acc);
  acc.finish(gripper_);
  return out;
}

std::vector<Check> check_candidates(const PointBvh& bvh, const Gripper& g,
                                    std::span<const Candidate> candidates) {
  std::vector<Check> out(candidates.size());
  const Checker check(bvh, g);
  tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t i) { out[i] = check(candidates[i]); });
  return out;
}


void closing_indices(const PointBvh& bvh, const Gripper& g, const Candidate& c,
                     std::vector<std::uint32_t>& out) {
  out.clear();
  if (bvh.empty()) return;
  const GripperLanes gl(g);
  const lanes::Frame4 to_gripper(c.rotation.transpose(), c.position);
  const LocalFrame f = local_frame(g, c, to_gripper);
  const Walker w{bvh, gl, f};
  // In the hierarchy's order, not sorted: the order is fixed by the hierarchy and the
  // candidate alone (so the same on any thread count), and sorting the ~10^3 indices of each of
  // the ~2 x 1,500 predictions was half the score stage (40-47 -> 21-25 ms, simulated frames).
  w.collect(bvh.top(), 0, out);
}

}  // namespace uwgrasp::grasp
