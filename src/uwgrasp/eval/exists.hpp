#pragma once
// Whether any grasp of the gripper holds the target at all, judged like every other grasp: when
// a detector answers "no feasible grasp", that is right only if none exists (a box lying flat,
// lower than a finger is long, has no grasp that keeps the fingers out of the seafloor). The
// search: antipodal pairs on the target's true surface (a point drawn by area, the closing axis
// along its inward normal, the far side where that axis leaves the object), each tried from
// `approaches` directions around the closing axis and at `depths` positions of the contacts
// along the fingers, from near their base to near their tips (to 95 % of the half length either
// way of the pads' centre). Contacts within the middle half of the pads only missed every grasp
// of a T-bar lying flat, whose holds close near the fingertips: a dense search (1,500 points,
// 24 approaches) found none that way and 1,329 along the whole pad.
#include <cstdint>

#include "uwgrasp/eval/judge.hpp"

namespace uwgrasp::eval {

struct ExistenceConfig {
  std::uint32_t points = 1000;
  std::uint32_t approaches = 16;
  std::uint32_t depths = 11;
  double mu = 0.4;
  std::uint64_t seed = 1;
};

struct Existence {
  bool exists = false;
  std::size_t tried = 0;                // grasps judged until the first that holds, or all
  Pose example = Pose::Identity();      // T_WG of the first that holds (lowest index)
};

// Throws Error for a target out of range.
Existence find_any_grasp(const sim::World& world, const Camera& camera, const grasp::Gripper& gripper,
                         int target, const ExistenceConfig& cfg = {});

}  // namespace uwgrasp::eval
