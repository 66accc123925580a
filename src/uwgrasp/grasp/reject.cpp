// The names and counts of the feasibility check's verdicts (feasibility.hpp).
#include "uwgrasp/grasp/feasibility.hpp"

namespace uwgrasp::grasp {

const char* reject_name(Reject r) {
  static const char* names[kRejectKinds] = {
      "feasible",       "collision_left_finger", "collision_right_finger",
      "collision_palm", "collision_body",        "empty",
      "too_narrow",     "too_wide",              "occluded",
      "not_antipodal",  "too_few_inliers",       "hull_collision",
      "scene_collision", "approach_blocked",     "cannot_hold",
      "not_robust"};
  return names[static_cast<int>(r)];
}

RejectCounts count_rejections(std::span<const Check> checks) {
  RejectCounts counts{};
  for (const Check& c : checks) ++counts[static_cast<int>(c.reason)];
  return counts;
}

}  // namespace uwgrasp::grasp
