#pragma once
// The checks a candidate must pass before it is scored, beyond the gripper against the object's
// points (feasibility.hpp): no solid part wholly inside the object's shape (shape.hpp), none in
// the object's shadow (occlusion.hpp), and the whole vehicle's reach (reach.hpp). One candidate
// at a time, so that the pool is checked in one pass and a sampler can try a draw's variants
// until one passes all of them.
#include <optional>
#include <vector>

#include "uwgrasp/grasp/feasibility.hpp"
#include "uwgrasp/grasp/occlusion.hpp"
#include "uwgrasp/grasp/reach.hpp"
#include "uwgrasp/grasp/shape.hpp"

namespace uwgrasp::grasp {

// The object's depth map and the gripper's part samples for the occlusion check.
struct Shadow {
  DepthMap map;
  PartSamples samples;
};

// The solid part (Part order) whose centre lies in an occupied voxel of `shape`, or -1.
int part_inside(const ObjectShape& shape, const Gripper& g, const Candidate& c);

struct GateInputs {
  const PointBvh& model;          // the object's points and unseen surface, L
  const Gripper& checked;         // the gripper as checked against them (grown by the margin)
  const Gripper& gripper;         // as built, for the vehicle's reach
  const ObjectShape& shape;       // empty: no shape check
  const Frames& frames;
  const Shadow* shadow = nullptr;  // null: no occlusion check
  const OcclusionConfig& occlusion;
  const ReachConfig& reach;
  const Surroundings& scene;      // the obstacles for the reach check
};

class Gate {
 public:
  // Throws Error for a reach configuration vehicle_solids rejects.
  explicit Gate(const GateInputs& in);
  // With the reach check's vehicle solids and obstacles made beforehand (vehicle_solids and
  // make_obstacles of in.scene, as the first constructor makes them), e.g. beside other work.
  Gate(const GateInputs& in, std::vector<Solid> solids, Obstacles obstacles);
  // Why a candidate that passed the gripper check fails the rest, in the detector's order
  // (inside the shape, occluded, unreachable); Reject::none when it passes.
  Reject after_check(const Candidate& c) const;
  // Whether it passes every check, the gripper's included; the cheapest first. When it does and
  // `check` is given, the gripper's check (closing region, contacts, width) is stored there.
  bool passes(const Candidate& c, Check* check = nullptr) const;
  // The reach check of the gripper's parts at the pose alone: scene_collision when one hits the
  // scene there (its points, the columns under them, the seafloor), else Reject::none (also
  // with the reach check off). Not the way in, and not the hull: a hull brushing the seafloor
  // under positioning error moves the vehicle, it does not stop the fingers closing.
  Reject gripper_at_pose(const Candidate& c) const;

 private:
  GateInputs in_;
  Checker check_;
  Pose camera_from_level_;
  std::vector<Solid> solids_;
  Obstacles obstacles_;
  ReachConfig at_pose_;  // in_.reach with no standoff
};

}  // namespace uwgrasp::grasp
