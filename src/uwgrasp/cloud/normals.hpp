#pragma once
// Surface normals and curvature from the local covariance (thesis 4.2.1, eq. 4.4-4.7).
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <span>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::cloud {

struct NormalConfig {
  std::uint32_t k = 20;  // neighbourhood size P^k (the point itself included)
  float radius = 0.0f;   // m; > 0 uses all points within the radius instead of k
};

struct PointNormal {
  Eigen::Vector3f normal = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
  float curvature = std::numeric_limits<float>::quiet_NaN();
};

// The smallest eigenvalue of a covariance (symmetric, positive semi-definite) and a unit
// eigenvector of it, and the matrix's trace (the sum of its eigenvalues, eq. 4.7's denominator).
// Newton's method on the characteristic polynomial and a cross product where the smallest root
// is separate (a surface's normal), Eigen's SelfAdjointEigenSolver::computeDirect where it is
// not. Eigen's closed form for all three took half of the organised normals stage; this takes
// about a third less (BM_OrgNormals on mOSD_learn0, one thread: 6.9 -> 6.2 ms).
struct SmallestEigen {
  double value = 0.0, trace = 0.0;
  Eigen::Vector3d vector = Eigen::Vector3d::UnitZ();
};
SmallestEigen smallest_eigen(const Eigen::Matrix3d& cov);

// Normal = eigenvector of the smallest eigenvalue of C (eq. 4.4 about the centroid, eq. 4.5),
// flipped so that n.(viewpoint - p) >= 0 (eq. 4.6); curvature = l0 / (l0 + l1 + l2) (eq. 4.7).
// Fewer than 3 neighbours gives NaN normal and curvature.
PointNormal normal_from(std::span<const Eigen::Vector3f> points,
                        std::span<const std::uint32_t> neighbours, const Eigen::Vector3f& at,
                        const Eigen::Vector3f& viewpoint);

// The same from the covariance C already computed (any positive scale).
PointNormal normal_from_covariance(const Eigen::Matrix3d& cov, const Eigen::Vector3f& at,
                                   const Eigen::Vector3f& viewpoint);

// Fills cloud.normals and cloud.curvature for every point (in parallel). Points must be finite.
void compute_normals(Cloud& cloud, const NormalConfig& cfg);

// The same from neighbour lists already computed for this cloud (nb.k >= min(cfg.k, size), kNN mode): the
// first cfg.k of each list are the k nearest, so the normals are identical.
void compute_normals(Cloud& cloud, const NormalConfig& cfg, const Neighbours& nb);

}  // namespace uwgrasp::cloud
