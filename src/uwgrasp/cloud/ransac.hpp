#pragma once
// RANSAC plane fit (thesis 4.1.4, Fischler & Bolles 1981) with the iteration count of eq. 4.3.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::cloud {

struct PlaneConfig {
  bool enabled = true;
  float distance = 0.01f;      // m; inlier tolerance (the first Fischler-Bolles threshold)
  double probability = 0.99;   // p of eq. 4.2-4.3; the thesis uses 99 % (8.2)
  std::uint32_t max_iterations = 20;  // explicit cap; the thesis sets k = 20 (8.2)
  double min_inlier_ratio = 0.05;     // a plane needs at least this share of the points
  bool refine = true;          // least-squares refit on the inliers, then reselect them
  bool required = false;       // no plane found is an error (otherwise the stage is a no-op)
  // > 0: the inlier band widens to this many times the depth noise measured on the plane at
  // each point's range (plane_noise.hpp); 0: the fixed `distance` alone (the thesis).
  float noise_sigmas = 3.0f;
  // > 0, organised frames: a point in the widened band but beyond `distance` stays off the plane
  // when its window's normal turns more than this many degrees from the plane's (the foot of an
  // object standing on it, not noisy floor); 0: the band alone.
  float normal_angle = 30.0f;
  // The plane is removed only when it supports the rest: most points off it lie between it and
  // the sensor (a seafloor, table or wall with objects in front). When most lie behind it, seen
  // from the sensor, and they are 5 % of its inliers or more, it is a face of the object itself
  // (an object-only scan) and stays; fewer are mismatches behind an opaque support.
  bool support_only = true;
};

struct PlaneResult {
  bool found = false;
  Eigen::Vector4f coefficients = Eigen::Vector4f::Zero();  // n.x n.y n.z d, |n| = 1, n.p + d = 0
  std::vector<std::uint32_t> inliers;                      // ascending
  std::uint32_t iterations = 0;                            // hypotheses drawn
};

// Eq. 4.3: k = log(1 - p) / log(1 - w^n), rounded up, at least 1. w is the inlier fraction.
double ransac_iterations(double p, double w, int n = 3);

// Fits the plane with the most inliers. Each hypothesis i draws its three points from
// Rng(seed, i), so the result depends only on the seed. After every improvement the iteration
// budget is recomputed from eq. 4.3 with w = best inliers / N, and never exceeds max_iterations.
// The plane normal points towards the cloud's viewpoint. Degenerate input (fewer than 3 points,
// all collinear) gives found = false.
PlaneResult fit_plane(const Cloud& in, const PlaneConfig& cfg, std::uint64_t seed);
// The same into `res`, reusing its inlier list's capacity.
void fit_plane(const Cloud& in, const PlaneConfig& cfg, std::uint64_t seed, PlaneResult& res);

// Least-squares plane through the points within tol of `plane` (eigenvector of the smallest
// covariance eigenvalue); `plane` itself when fewer than three are.
Eigen::Vector4f least_squares_plane(const Cloud& in, const Eigen::Vector4f& plane, float tol);

}  // namespace uwgrasp::cloud
