#pragma once
// Internal to grasp/: drawing the candidates for detector.cpp's find_grasps - the chosen
// sampler, or the automatic choice among them (thesis 9.3), each draw's candidates checked
// against the gripper unless the gate already checked them while drawing - into one pool.
#include <cstdint>
#include <optional>
#include <vector>

#include "uwgrasp/core/timer.hpp"
#include "uwgrasp/grasp/bvh.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/grasp/gate.hpp"

namespace uwgrasp::grasp {

struct LevelCloud {
  std::vector<Eigen::Vector3f> points, normals;
};

// What the samplers draw from: the visible points (L), the object's model (its visible points
// and unseen surface, L) and its shape.
struct SampleInputs {
  const LevelCloud& l;
  const LevelCloud& model;
  const ObjectShape& shape;
  const Gripper& gripper;  // as checked (grown by the margin)
  const Gate& gate;  // every check before scoring
  const std::optional<Eigen::Vector4f>& floor;  // the seafloor in L, when the scene has one
};

// The candidates drawn and, for those that passed every check while drawn (only the antipodal
// sampler checks as it draws), `passed` and their gripper check: those need not be checked again.
struct Drawn {
  std::vector<Candidate> candidates;
  std::vector<char> passed;
  std::vector<Check> checks;
};

struct Pool {
  std::vector<Candidate> candidates;
  std::vector<Check> checks;
  std::vector<char> gated;  // passed every check while sampling
  void add(Drawn d) {
    gated.insert(gated.end(), d.passed.begin(), d.passed.end());
    candidates.insert(candidates.end(), d.candidates.begin(), d.candidates.end());
    checks.insert(checks.end(), d.checks.begin(), d.checks.end());
  }
};

// Draws `count` candidates (the first numbered `first`) with `kind` and checks those the drawing
// did not, timed as the sample and check stages.
Drawn draw_checked(SamplerKind kind, const SampleInputs& in, const GraspConfig& cfg, const Frames& f,
                   const PointBvh& bvh, std::uint64_t seed, std::uint32_t count, std::uint32_t first,
                   StageTimer& timer);

// automatic: a pilot share on each sampler, then the rest of the budget on the one that found
// the most feasible candidates (ties: normal, uniform, surface, antipodal - the thesis's order of
// use, then ours; antipodal only when the object has a shape model to close on).
SamplerKind run_auto(const SampleInputs& in, const GraspConfig& cfg, const Frames& f, const PointBvh& bvh,
                     std::uint64_t seed, StageTimer& timer, Pool& pool);

}  // namespace uwgrasp::grasp
