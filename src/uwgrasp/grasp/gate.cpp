#include "uwgrasp/grasp/gate.hpp"

#include <span>
#include <utility>

namespace uwgrasp::grasp {

int part_inside(const ObjectShape& shape, const Gripper& g, const Candidate& c) {
  if (shape.empty()) return -1;
  for (int part = 0; part < kParts; ++part)
    if (shape.occupied(c.rotation * g.solids[std::size_t(part)].centre() + c.position)) return part;
  return -1;
}

namespace {
ReachConfig without_standoff(ReachConfig r) {
  r.standoff = 0.0;
  return r;
}
}  // namespace

Gate::Gate(const GateInputs& in)
    : in_(in),
      check_(in.model, in.checked),
      camera_from_level_(in.frames.level_from_camera.inverse()),
      at_pose_(without_standoff(in.reach)) {
  if (!in.reach.enabled) return;
  solids_ = vehicle_solids(in.gripper, in.frames, in.reach);
  obstacles_ = make_obstacles(in.scene, in.frames, in.reach);
}

Gate::Gate(const GateInputs& in, std::vector<Solid> solids, Obstacles obstacles)
    : in_(in),
      check_(in.model, in.checked),
      camera_from_level_(in.frames.level_from_camera.inverse()),
      solids_(std::move(solids)),
      obstacles_(std::move(obstacles)),
      at_pose_(without_standoff(in.reach)) {}

Reject Gate::after_check(const Candidate& c) const {
  if (const int part = part_inside(in_.shape, in_.checked, c); part >= 0)
    return static_cast<Reject>(int(Reject::collision_left_finger) + part);
  if (in_.shadow && occluded(in_.shadow->map, in_.shadow->samples, c, camera_from_level_, in_.occlusion))
    return Reject::occluded;
  return in_.reach.enabled ? reach_check(obstacles_, solids_, c, in_.reach) : Reject::none;
}

bool Gate::passes(const Candidate& c, Check* check) const {
  // A few voxel lookups and the hull's corners against the seafloor first: most failing draws
  // stop there, before any walk of a point hierarchy.
  if (part_inside(in_.shape, in_.checked, c) >= 0) return false;
  if (in_.reach.enabled && reach_plane_check(obstacles_, solids_, c, in_.reach) != Reject::none) return false;
  const Check k = check_(c);
  if (!k.feasible() || after_check(c) != Reject::none) return false;
  if (check) *check = k;
  return true;
}

Reject Gate::gripper_at_pose(const Candidate& c) const {
  // [0] is the hull (vehicle_solids' order); a gate given no solids has no gripper to place.
  if (!in_.reach.enabled || solids_.size() < 2) return Reject::none;
  return reach_check(obstacles_, std::span(solids_).subspan(1), c, at_pose_);
}

}  // namespace uwgrasp::grasp
