#include "uwgrasp/eval/judge.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/eval/steps.hpp"

namespace uwgrasp::eval {

const char* verdict_name(Verdict v) {
  static const char* names[kVerdicts] = {"closes",       "collision", "miss",
                                         "other_object", "too_wide",  "too_narrow"};
  return names[static_cast<int>(v)];
}

Judgement judge(const sim::World& world, const Camera& camera, const grasp::Gripper& gripper,
                const Pose& T, int target, const JudgeConfig& cfg) {
  const int objects = static_cast<int>(world.scene().objects.size());
  if (target < 0 || target >= objects)
    throw Error("judge: target object " + std::to_string(target) + " is not one of the scene's " +
                std::to_string(objects) + " objects");
  if (!T.matrix().allFinite()) throw Error("judge: the grasp pose is not finite");
  // Poses arrive through float detectors, JSON digits and products of frames: a rotation a few
  // 1e-7 from orthonormal is one (re-orthonormalised, so the pads' rays stay unit); one far
  // from it is not a pose.
  const Eigen::Matrix3d R = T.linear();
  if (!((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-3) || R.determinant() < 0.0)
    throw Error("judge: the grasp pose's orientation is not a rotation");
  Pose G = T;
  G.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();
  Judgement j;
  if (detail::collides(world, camera, gripper, G, cfg, j)) return j;
  detail::close_pads(world, gripper, G, target, cfg, j);
  return j;
}

Pose perturbed(const Pose& T, const RobustConfig& cfg, std::uint64_t seed, std::uint64_t stream,
               std::uint32_t k) {
  Rng rng(seed ^ 0x6A09E667F3BCC908ULL, (stream << 24) ^ k);
  Eigen::Vector3d d, w;
  for (int i = 0; i < 3; ++i) d[i] = rng.normal(0.0, cfg.sigma_position);
  for (int i = 0; i < 3; ++i) w[i] = rng.normal(0.0, cfg.sigma_angle);
  Pose out = T;
  out.translation() += d;
  if (w.norm() > 0.0) out.linear() = T.linear() * Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  return out;
}

double robust_share(const sim::World& world, const Camera& camera, const grasp::Gripper& gripper,
                    const Pose& T, int target, const RobustConfig& cfg, std::uint64_t seed,
                    std::uint64_t stream, const JudgeConfig& judge_cfg) {
  if (cfg.samples == 0) throw Error("robust force closure needs at least one perturbed pose");
  if (!(cfg.mu > 0.0)) throw Error("robust force closure: mu must be positive");
  std::vector<char> held(cfg.samples, 0);
  tbb::parallel_for(std::uint32_t(0), cfg.samples, [&](std::uint32_t k) {
    held[k] = judge(world, camera, gripper, perturbed(T, cfg, seed, stream, k), target, judge_cfg)
                  .holds(cfg.mu);
  });
  return double(std::count(held.begin(), held.end(), 1)) / double(cfg.samples);
}

}  // namespace uwgrasp::eval
