#pragma once
// Feasibility (thesis 6.1, 7.4.3): a candidate is rejected when an object point lies in a solid
// part of the gripper (fingers at full aperture, palm, body behind the palm) - the thesis's "in
// the collision box but not in the closing region" - when its closing region holds no point, or
// when the object's width at closure is outside what the gripper can hold.
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "uwgrasp/grasp/bvh.hpp"
#include "uwgrasp/grasp/gripper.hpp"
#include "uwgrasp/grasp/samplers.hpp"

namespace uwgrasp::grasp {

enum class Reject : std::uint8_t {
  none,
  collision_left_finger,
  collision_right_finger,
  collision_palm,
  collision_body,
  empty,          // no point in the closing region
  too_narrow,     // width at closure below the minimum aperture
  too_wide,       // width at closure above max_aperture - 2 * clearance
  occluded,       // a solid part in the object's unseen shadow (see occlusion.hpp)
  not_antipodal,  // contacts outside each other's friction cone (only when required)
  too_few_inliers,  // fewer closing-region points than score.inliers.min (see score.hpp)
  hull_collision,    // the vehicle's hull hits the scene at the grasp pose (see reach.hpp)
  scene_collision,   // a gripper part hits the scene (not the object) or the seafloor there
  approach_blocked,  // hull or gripper hits the scene on the way in from the standoff
  cannot_hold,       // holding the vehicle's attitude needs more than its thrusters give
  not_robust,        // holds on the model in under robust.min_robustness of its perturbed poses
};
inline constexpr int kRejectKinds = 16;
const char* reject_name(Reject r);

// What the check learns about a candidate. Indices are cloud indices; ties go to the lowest.
struct Check {
  Reject reason = Reject::none;
  std::uint32_t inliers = 0;  // points in the closing region
  std::uint32_t nearest = 0;  // the closing-region point nearest the gripper position (6.2)
  // Contacts: the closing-region points nearest each finger plane (6.4), i.e. lowest and
  // highest along the closing direction, and their distance along it - the width at closure.
  std::uint32_t left = 0, right = 0;
  float width = 0.0f;
  bool feasible() const { return reason == Reject::none; }
};

using RejectCounts = std::array<std::size_t, kRejectKinds>;

// The check of one candidate at a time against the points under `bvh` (for samplers that try
// a candidate's variants until one passes); cheap to copy, valid while bvh and g live.
class Checker {
 public:
  Checker(const PointBvh& bvh, const Gripper& g);
  Check operator()(const Candidate& c) const;
  // The first solid part a point lies in (Reject::none: none), without the closing region.
  Reject solids(const Candidate& c) const;

 private:
  struct State;
  const Gripper& gripper_;
  std::shared_ptr<const State> state_;
};

// Checks every candidate against the points under `bvh`, in parallel (result i for candidate i):
// first the solid parts, stopping at the first point inside one, then the closing region.
std::vector<Check> check_candidates(const PointBvh& bvh, const Gripper& g,
                                    std::span<const Candidate> candidates);

// The thesis's method (6.1, 8.4): every point of the cloud against the candidate's boxes. The
// same answer as check_candidates (up to which solid part is named when several are hit); the
// oracle in tests and the baseline in benchmarks.
Check check_brute(std::span<const Eigen::Vector3f> points, const Gripper& g, const Candidate& c);

// Cloud indices of the closing-region points of a candidate (for pictures and tests).
std::vector<std::uint32_t> closing_points(std::span<const Eigen::Vector3f> points,
                                          const Gripper& g, const Candidate& c);

// The same through the hierarchy: the cloud indices of the points in the candidate's closing
// region, in `out`, in the hierarchy's (deterministic, not ascending) order.
void closing_indices(const PointBvh& bvh, const Gripper& g, const Candidate& c,
                     std::vector<std::uint32_t>& out);

// Counts per reason; counts[none] is the number of feasible candidates.
RejectCounts count_rejections(std::span<const Check> checks);

}  // namespace uwgrasp::grasp
