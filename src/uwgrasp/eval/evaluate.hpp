#pragma once
// A detector's ranked grasps judged against the truth in one call: every grasp judged (in
// parallel), the summary metrics, and the robust force closure of the best-ranked grasp.
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "uwgrasp/eval/judge.hpp"
#include "uwgrasp/eval/summary.hpp"

namespace uwgrasp::eval {

struct Evaluation {
  std::vector<Judgement> judgements;  // the first cfg.top grasps, in rank order
  Summary summary;
  double robust_top1 = std::numeric_limits<double>::quiet_NaN();  // NaN: no grasp, or not asked
};

// `ranked`: grasp poses T_WG, best first. robust.samples = 0 skips the robustness of the top-1.
// Same seed, same result at any thread count. Throws Error for a bad summary config or target.
Evaluation evaluate(const sim::World& world, const Camera& camera, const grasp::Gripper& gripper,
                    std::span<const Pose> ranked, int target, const SummaryConfig& cfg,
                    const RobustConfig& robust, std::uint64_t seed,
                    const JudgeConfig& judge_cfg = {});

}  // namespace uwgrasp::eval
