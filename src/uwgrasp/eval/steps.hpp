#pragma once
// Internal to eval/: the steps of judge() (judge.hpp).
#include "uwgrasp/eval/judge.hpp"

namespace uwgrasp::eval::detail {

// Step 1: true (and j filled) when a solid part collides with an object or the seafloor.
bool collides(const sim::World& world, const Camera& camera, const grasp::Gripper& gripper,
              const Pose& world_from_gripper, const JudgeConfig& cfg, Judgement& j);

// Steps 2 and 3: the pads close on the target; fills verdict, width, contacts and mu_min.
void close_pads(const sim::World& world, const grasp::Gripper& gripper,
                const Pose& world_from_gripper, int target, const JudgeConfig& cfg, Judgement& j);

// Whether the camera saw the surface point p (in its image, in range, nothing nearer on the way).
bool visible(const sim::World& world, const Camera& camera, const Eigen::Vector3d& p,
             double tolerance);

}  // namespace uwgrasp::eval::detail
