#include "uwgrasp/grasp/score.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <optional>
#include <cmath>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::grasp {

double robust_total(const Grasp& g) {
  // The attitude: q_o (roll, pitch and yaw from the capture attitude: a vehicle that must turn
  // round to come from the unseen side pays for it), averaged with q_v when a model prices it.
  const double attitude = std::isfinite(g.hold_cost) ? 0.5 * (g.scores.orientation + g.scores.vehicle)
                                                     : g.scores.orientation;
  return g.robustness + 0.2 * g.force_closure + 0.1 * attitude;
}

Grasp score_candidate(std::span<const Eigen::Vector3f> points,
                      std::span<const Eigen::Vector3f> normals, const Candidate& c,
                      const Check& check, const Frames& frames, const ScoreConfig& cfg,
                      double max_inliers, const ContactPrediction* predicted) {
  Grasp g;
  g.level_from_gripper = Pose::Identity();
  g.level_from_gripper.linear() = c.rotation.cast<double>();
  g.level_from_gripper.translation() = c.position.cast<double>();
  g.level_from_vehicle = vehicle_pose(g.level_from_gripper, frames);
  g.vehicle_rpy = rpy_from_matrix(g.level_from_vehicle.linear());
  g.inliers = check.inliers;
  g.width = check.width;
  // q_n: the closing-region point nearest the gripper position (6.2).
  const Eigen::Vector3d approach = c.rotation.col(0).cast<double>();
  g.scores.normal = normal_score(approach, normals[check.nearest].cast<double>());
  g.scores.orientation = orientation_score(g.vehicle_rpy, cfg.orientation);

  g.contact_index[0] = check.left, g.contact_index[1] = check.right;
  g.contacts[0] = points[check.left].cast<double>();
  g.contacts[1] = points[check.right].cast<double>();
  const ContactScores cs =
      contact_scores(g.contacts[0], g.contacts[1], normals[check.left].cast<double>(),
                     normals[check.right].cast<double>(), c.rotation.col(1).cast<double>());
  g.scores.contact_left = cs.left;
  g.scores.contact_right = cs.right;
  g.friction = antipodal(cs, cfg.mu);
  g.scores.inliers = inlier_score(g.inliers, max_inliers);
  if (cfg.hold_cost) {
    g.hold_cost = cfg.hold_cost(g.vehicle_rpy);
    g.scores.vehicle = std::clamp(1.0 - g.hold_cost, 0.0, 1.0);
  }
  g.scores.total = total_score(g.scores, cfg.weights);
  if (predicted != nullptr) {
    // What the model says: both contacts, the width from both sides, the friction estimate.
    g.width = predicted->width;
    for (int s = 0; s < 2; ++s) g.contacts[s] = predicted->contact[s].cast<double>(), g.contact_seen[s] = predicted->seen[s];
    g.friction = {predicted->valid && predicted->mu <= cfg.mu, double(predicted->mu)};
    g.force_closure = predicted->valid ? std::clamp(1.0 - predicted->mu / cfg.robust.mu, 0.0, 1.0) : 0.0;
    g.scores.total = robust_total(g);
  }
  return g;
}

std::vector<Grasp> score_all(std::span<const Eigen::Vector3f> points,
                             std::span<const Eigen::Vector3f> normals,
                             std::span<const Candidate> candidates, std::vector<Check>& checks,
                             const Frames& frames, const ScoreConfig& cfg, double max_inliers,
                             std::span<const ContactPrediction> predicted) {
  std::vector<std::uint32_t> feasible;
  for (std::size_t i = 0; i < checks.size(); ++i) {
    if (checks[i].feasible() && checks[i].inliers < cfg.min_inliers) checks[i].reason = Reject::too_few_inliers;
    if (checks[i].feasible()) feasible.push_back(static_cast<std::uint32_t>(i));
  }
  std::vector<Grasp> all(feasible.size());
  tbb::parallel_for(std::size_t(0), feasible.size(), [&](std::size_t k) {
    const std::uint32_t i = feasible[k];
    all[k] = score_candidate(points, normals, candidates[i], checks[i], frames, cfg, max_inliers,
                             predicted.empty() ? nullptr : &predicted[i]);
    all[k].candidate = i;
  });
  std::erase_if(all, [&](const Grasp& g) {
    if (cfg.require_antipodal && !g.friction.ok) checks[g.candidate].reason = Reject::not_antipodal;
    else if (g.hold_cost > 1.0) checks[g.candidate].reason = Reject::cannot_hold;
    else return false;
    return true;
  });
  return all;
}

void rank(std::vector<Grasp>& all, std::size_t top) {
  const auto better = [](const Grasp& a, const Grasp& b) {
    if (a.scores.total != b.scores.total) return a.scores.total > b.scores.total;
    return a.candidate < b.candidate;
  };
  const std::size_t keep = std::min(top, all.size());
  std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(keep), all.end(), better);
  all.resize(keep);
}

std::vector<Grasp> score_and_rank(std::span<const Eigen::Vector3f> points,
                                  std::span<const Eigen::Vector3f> normals,
                                  std::span<const Candidate> candidates, std::vector<Check>& checks,
                                  const Frames& frames, const ScoreConfig& cfg, double max_inliers) {
  std::vector<Grasp> all = score_all(points, normals, candidates, checks, frames, cfg, max_inliers);
  rank(all, cfg.top);
  return all;
}

namespace {
// Median distance to the nearest neighbour: the cloud's own "voxel size" when none was set.
double median_spacing(std::span<const Eigen::Vector3f> pts, const cloud::KdTree* shared) {
  std::optional<cloud::KdTree> own;
  const cloud::KdTree& tree = shared ? *shared : own.emplace(pts);
  const cloud::Neighbours nb = cloud::knn_all(tree, pts, 2);
  std::vector<float> d;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (nb.count[i] > 1) d.push_back(std::sqrt(nb.dists_of(i)[1]));
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}
}  // namespace

double max_inliers(const ScoreConfig& s, const Gripper& g, std::span<const Eigen::Vector3f> points, double leaf,
                   const cloud::KdTree* tree) {
  if (s.inlier_mode == InlierMode::fixed) return s.max_inliers;
  if (!(leaf > 0.0)) leaf = median_spacing(points, tree);
  if (!(leaf > 0.0)) throw Error("derived maximum inliers: the object's points all coincide");
  const Eigen::Vector3f size = g.closing.hi - g.closing.lo;
  return s.inlier_mode == InlierMode::volume ? max_inliers_volume(size, leaf)
                                             : max_inliers_surface(size, leaf);
}

}  // namespace uwgrasp::grasp
