#pragma once
// The contacts a grasp makes, predicted on the object's model - its visible points and its
// unseen surface (shape.hpp) - the way the judge finds them on the true shape (eval/judge.hpp),
// so that the detector's friction estimate means what the judge's does: each pad stops at the
// model's extreme along the closing axis; its contact patch is the model's points within `band`
// of that extreme; the line of action runs along the closing axis through the middle of the two
// patches; the contacts are the model's first points along that line from either side (within
// `radius` of it), with the mean of their normals; force closure as in metrics.hpp.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <span>

#include "uwgrasp/grasp/samplers.hpp"

namespace uwgrasp::grasp {

struct ContactPrediction {
  bool valid = false;  // both sides found
  Eigen::Vector3f contact[2] = {Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero()};  // L: left, right
  Eigen::Vector3f normal[2] = {Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero()};   // outward
  float width = 0.0f;                                      // pads' separation at closure, m
  float mu = std::numeric_limits<float>::infinity();       // smallest mu for force closure
  Eigen::Vector2f line = Eigen::Vector2f::Zero();          // the line's (x, z) on the pads, m
  bool seen[2] = {false, false};  // the contact is on measured points (else on the unseen model)
};

// `closing`: the indices of the model points in the candidate's closing region (feasibility's
// closing_indices). Points and normals in L; the first `measured` points are the camera's, the
// rest the unseen model's.
ContactPrediction predict_contacts(std::span<const Eigen::Vector3f> points,
                                   std::span<const Eigen::Vector3f> normals,
                                   std::span<const std::uint32_t> closing, const Candidate& c,
                                   float band, float radius, std::size_t measured);

}  // namespace uwgrasp::grasp
