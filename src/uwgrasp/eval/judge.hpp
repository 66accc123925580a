#pragma once
// Ground-truth grasp judging. The thesis judged its grasps "by inspection" (8.5); here a grasp is
// put into the simulated world it was detected in and judged against the objects' full shapes:
//  1. collision: the gripper's solid parts (fingers at full aperture, palm, body; gripper.hpp)
//     against every object and the seafloor, exactly (triangles clipped by each part's box, and
//     parts wholly inside an object), ignoring penetrations up to `tolerance`;
//  2. closing: each finger pad closes along the closing axis until it touches something (a grid
//     of rays from the pad's inner face); the width at closure is the pads' separation. Nothing
//     between the pads is a miss, another object or the seafloor touched first is other_object,
//     a width above the usable aperture (max_aperture - 2 clearance) is too_wide;
//  3. force closure of the two contacts under Coulomb friction (Nguyen 1988; Murray, Li &
//     Sastry 5.2, the condition of thesis 6.4): the line between the contacts lies in both
//     friction cones. As in Dex-Net and graspnetAPI, the contacts lie on one line of action
//     along the closing axis, with the object's surface normals there. Dex-Net's line runs
//     through the grasp centre; here it runs through the midpoint of the two pads' contact
//     patches (the surface within `compliance` of each pad's first touch), i.e. through where
//     the pads actually press - on a cylinder grasped off-centre, through its axis;
//  4. robust force closure (Dex-Net's robustness under pose noise): the share of seeded
//     perturbed poses that still hold.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/grasp/gripper.hpp"
#include "uwgrasp/grasp/metrics.hpp"
#include "uwgrasp/sim/query.hpp"

namespace uwgrasp::eval {

// The camera that saw the scene: decides whether a touched surface was visible.
struct Camera {
  Pose world_from_camera = Pose::Identity();
  sim::Intrinsics intrinsics;
  double max_range = 6.0;
};

struct JudgeConfig {
  double tolerance = 0.001;    // m: parts may sink this far into a surface (positioning slack)
  double pad_spacing = 0.002;  // m between the fallback lines of action on a finger pad
  double compliance = 0.0005;  // m the pads give: surface this close to a first touch presses too
  double visibility_tolerance = 0.002;  // m: a surface point is seen if nothing is this much nearer
};

enum class Verdict : std::uint8_t { closes, collision, miss, other_object, too_wide, too_narrow };
inline constexpr int kVerdicts = 6;
const char* verdict_name(Verdict v);

struct Judgement {
  Verdict verdict = Verdict::miss;
  // collision: the first solid part in grasp::Part order that hits, what it hits (an object
  // index or sim::kSeafloorObject), whether the camera saw the surface it crosses, and whether
  // it lies wholly inside the object (no surface crossed at all).
  // other_object: `object` is what the pads touched first.
  int part = -1;
  int object = sim::kNoObject;
  bool visible = false;
  bool inside = false;
  // closing (closes, too_wide, too_narrow): pad separation at closure, m
  double width = 0.0;
  // closes: the contacts in W (left pad, right pad), the outward surface normals there, and the
  // smallest friction coefficient for force closure (+inf: no friction suffices)
  Eigen::Vector3d contacts[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  Eigen::Vector3d normals[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  double mu_min = std::numeric_limits<double>::infinity();
  bool holds(double mu) const { return verdict == Verdict::closes && mu_min <= mu; }
};

// Judges the gripper at T_WG grasping object `target` (an index into the world's objects).
// Throws Error for a target out of range or a non-finite pose.
Judgement judge(const sim::World& world, const Camera& camera, const grasp::Gripper& gripper,
                const Pose& world_from_gripper, int target, const JudgeConfig& cfg = {});

// The force-closure condition is the grasp engine's own (grasp/metrics.hpp), so that the
// detector's predictions and the judge agree on what holds.
using grasp::force_closure_mu;

struct RobustConfig {
  std::uint32_t samples = 25;
  double sigma_position = 0.005;                // m per axis
  double sigma_angle = 3.0 * 3.141592653589793 / 180.0;  // rad per axis (rotation vector)
  double mu = 0.4;
};

// The pose perturbed by draw k of stream `stream`: T * [Rot(w), d] with d, w ~ N(0, sigma).
Pose perturbed(const Pose& world_from_gripper, const RobustConfig& cfg, std::uint64_t seed,
               std::uint64_t stream, std::uint32_t k);

// Share of cfg.samples perturbed poses that hold at cfg.mu (Dex-Net's robust force closure).
// The same seed and stream give the same share at any thread count.
double robust_share(const sim::World& world, const Camera& camera, const grasp::Gripper& gripper,
                    const Pose& world_from_gripper, int target, const RobustConfig& cfg,
                    std::uint64_t seed, std::uint64_t stream, const JudgeConfig& judge_cfg = {});

}  // namespace uwgrasp::eval
