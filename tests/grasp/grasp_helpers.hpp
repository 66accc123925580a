#pragma once
// Helpers for the grasp tests: hand-placed candidates and boxes with exact normals.
#include <Eigen/Geometry>
#include <span>
#include <vector>

#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/grasp/bvh.hpp"
#include "uwgrasp/grasp/feasibility.hpp"

namespace uwgrasp::test {

// A candidate at `position` approaching along `approach` with the fingers closing along
// `closing` (made orthogonal to the approach).
inline grasp::Candidate candidate(const Eigen::Vector3f& position, const Eigen::Vector3f& approach,
                                  const Eigen::Vector3f& closing) {
  grasp::Candidate c;
  const Eigen::Vector3f x = approach.normalized();
  const Eigen::Vector3f y = (closing - closing.dot(x) * x).normalized();
  c.rotation.col(0) = x;
  c.rotation.col(1) = y;
  c.rotation.col(2) = x.cross(y);
  c.position = position;
  return c;
}

// Every face of the box [lo, hi] sampled with spacing `step`, with outward face normals.
inline Cloud solid_box(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, float step) {
  Cloud c;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, d = (a + 2) % 3;
    const int nb = int((hi[b] - lo[b]) / step + 0.5f), nd = int((hi[d] - lo[d]) / step + 0.5f);
    for (int i = 0; i <= nb; ++i)
      for (int j = 0; j <= nd; ++j)
        for (int side = 0; side < 2; ++side) {
          Eigen::Vector3f p, n = Eigen::Vector3f::Zero();
          p[a] = side ? hi[a] : lo[a];
          p[b] = lo[b] + (hi[b] - lo[b]) * float(i) / float(nb);
          p[d] = lo[d] + (hi[d] - lo[d]) * float(j) / float(nd);
          n[a] = side ? 1.0f : -1.0f;
          c.points.push_back(p);
          c.normals.push_back(n);
        }
  }
  make_unorganised(c);
  return c;
}

// Checks one candidate through the BVH.
inline grasp::Check check_one(const Cloud& cloud, const grasp::Gripper& g, const grasp::Candidate& c) {
  const grasp::PointBvh bvh = grasp::build_bvh(cloud.points);
  return grasp::check_candidates(bvh, g, std::span<const grasp::Candidate>(&c, 1)).front();
}

inline bool is_collision(grasp::Reject r) {
  return r == grasp::Reject::collision_left_finger || r == grasp::Reject::collision_right_finger ||
         r == grasp::Reject::collision_palm || r == grasp::Reject::collision_body;
}

}  // namespace uwgrasp::test
