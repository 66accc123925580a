#pragma once
// Scoring and ranking of the feasible candidates (thesis 6.2-6.6).
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/grasp/feasibility.hpp"
#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/grasp/metrics.hpp"
#include "uwgrasp/grasp/robust.hpp"

namespace uwgrasp::grasp {

// How q_i's maximum is set (6.5): by hand as in Table 8.5, or derived from the gripper and the
// voxel size (see max_inliers_volume / max_inliers_surface).
enum class InlierMode { fixed, volume, surface };

// The vehicle's cost of holding the attitude (roll, pitch, yaw of T_LB) a grasp needs: the share
// of the thrusters' limit the hold takes (vehicle::hold_cost), above 1 when it cannot be held.
// Passed in by the caller, so the grasp engine needs no vehicle model; it must be thread-safe.
using HoldCostFn = std::function<double(const Eigen::Vector3d& rpy)>;

// How the total ranks grasps. thesis: q_tot of eq. 6.8 (plus w_v q_v), from the one-sided cloud
// the camera saw. robust (default): what the judge would find, predicted on the object's model
// (shape.hpp, contacts.hpp, robust.hpp): total = robustness + 0.2 q_fc + 0.1 q_a, where q_fc =
// 1 - mu_predicted / robust.mu (0 past it), robustness is the share of perturbed poses that hold
// on the model (measured for the robust.candidates best by q_fc, 0 for the others), and q_a is
// q_o, averaged with q_v when a vehicle model prices the hold. The thesis's scores are still
// computed and reported.
enum class ScoreMode { thesis, robust };

struct ScoreConfig {
  ScoreMode mode = ScoreMode::robust;
  RobustConfig robust;
  Weights weights;
  OrientationConfig orientation;
  InlierMode inlier_mode = InlierMode::fixed;
  double max_inliers = 135;     // Table 8.5 (barbell, circle); 250 for the cross
  // Fewer closing-region points than this and the grasp is rejected (too_few_inliers): a few
  // points - a fragment, a lone edge, noise - make q_n and q_c look perfect (6.2, 6.4) while
  // saying nothing of the surface the fingers will meet. Not in the thesis (it only rejects an
  // empty closing region); lower it for clouds sparser than ~5 mm between points.
  std::uint32_t min_inliers = 10;
  double mu = 0.5;              // friction coefficient for the antipodal test
  bool require_antipodal = false;  // reject grasps that are not antipodal for mu
  std::uint32_t top = 10;       // grasps kept after ranking
  // Empty: no hold cost, q_v = 0 (weights.vehicle must then be 0). Set: q_v = 1 - cost, and
  // grasps whose attitude cannot be held are rejected as cannot_hold.
  HoldCostFn hold_cost;
};

struct Grasp {
  std::uint32_t candidate = 0;     // index into the candidate list
  Pose level_from_gripper;         // T_LG
  Pose level_from_vehicle;         // T_LB = T_LG * T_BG^-1, the pose the vehicle must hold
  Eigen::Vector3d vehicle_rpy = Eigen::Vector3d::Zero();
  Scores scores;
  std::size_t inliers = 0;
  double width = 0.0;              // at closure, along the closing direction
  std::uint32_t contact_index[2] = {0, 0};  // object points: left, right
  Eigen::Vector3d contacts[2];     // in L
  bool contact_seen[2] = {true, true};  // on the camera's points (robust mode: else the model's)
  Antipodal friction;
  double hold_cost = std::numeric_limits<double>::quiet_NaN();  // utilisation; NaN: not computed
  // robust mode: the predicted force-closure score q_fc and the robustness on the model
  double force_closure = 0.0, robustness = 0.0;
  std::uint32_t robust_poses = 0;  // the perturbed poses its robustness was measured on
};

// Scores every feasible candidate (points and normals in L, indices as in the checks), in
// candidate order. A candidate with fewer than cfg.min_inliers points has its check's reason set
// to too_few_inliers, one that fails the antipodal requirement to not_antipodal, and one whose
// attitude the vehicle cannot hold to cannot_hold. `predicted` (robust mode, one per candidate,
// empty otherwise) gives the contacts, width and friction estimate from the object's model.
std::vector<Grasp> score_all(std::span<const Eigen::Vector3f> points,
                             std::span<const Eigen::Vector3f> normals,
                             std::span<const Candidate> candidates, std::vector<Check>& checks,
                             const Frames& frames, const ScoreConfig& cfg, double max_inliers,
                             std::span<const ContactPrediction> predicted = {});

// The grasps ranked by total score, ties by candidate index, at most `top`.
void rank(std::vector<Grasp>& grasps, std::size_t top);

// score_all then rank to cfg.top (the thesis mode's whole scoring stage).
std::vector<Grasp> score_and_rank(std::span<const Eigen::Vector3f> points,
                                  std::span<const Eigen::Vector3f> normals,
                                  std::span<const Candidate> candidates, std::vector<Check>& checks,
                                  const Frames& frames, const ScoreConfig& cfg, double max_inliers);

// Scores one feasible candidate; with a prediction (robust mode) its contacts, width and
// friction estimate come from it.
Grasp score_candidate(std::span<const Eigen::Vector3f> points,
                      std::span<const Eigen::Vector3f> normals, const Candidate& c,
                      const Check& check, const Frames& frames, const ScoreConfig& cfg,
                      double max_inliers, const ContactPrediction* predicted = nullptr);

// The robust mode's total from a grasp's scores, q_fc and robustness (see ScoreMode).
double robust_total(const Grasp& g);

// q_i's maximum (6.5): s.max_inliers when fixed, else derived from the gripper's closing region
// and the voxel size `leaf` (the points' median spacing when 0, searched in `tree` when given: a
// k-d tree over `points`). Throws Error when the points all coincide.
double max_inliers(const ScoreConfig& s, const Gripper& g, std::span<const Eigen::Vector3f> points, double leaf,
                   const cloud::KdTree* tree = nullptr);

}  // namespace uwgrasp::grasp
