#include "uwgrasp/eval/evaluate.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace uwgrasp::eval {

Evaluation evaluate(const sim::World& world, const Camera& camera, const grasp::Gripper& gripper,
                    std::span<const Pose> ranked, int target, const SummaryConfig& cfg,
                    const RobustConfig& robust, std::uint64_t seed, const JudgeConfig& judge_cfg) {
  check_summary(cfg);
  Evaluation e;
  const std::size_t n = std::min(ranked.size(), cfg.top);
  e.judgements.resize(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    e.judgements[i] = judge(world, camera, gripper, ranked[i], target, judge_cfg);
  });
  e.summary = summarise(e.judgements, cfg);
  if (n > 0 && robust.samples > 0)
    e.robust_top1 = robust_share(world, camera, gripper, ranked[0], target, robust, seed, 0, judge_cfg);
  return e;
}

}  // namespace uwgrasp::eval
