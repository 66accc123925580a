#include "uwgrasp/cloud/normals.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

SmallestEigen smallest_eigen(const Eigen::Matrix3d& cov) {
  SmallestEigen out;
  const double scale = cov.cwiseAbs().maxCoeff();
  if (scale > 0.0 && std::isfinite(scale)) {
    const Eigen::Matrix3d m = cov / scale;
    // Newton's method on det(l I - m) = l^3 - c2 l^2 + c1 l - c0 from l = 0: for a covariance
    // (eigenvalues >= 0) the polynomial is increasing and concave below its smallest root, so
    // the steps rise to it without overshooting. Quadratic for a separate root (a surface's
    // normal: a few steps); slow only where the root is (nearly) double - left to Eigen.
    const double c2 = m.trace(),
                 c1 = m(0, 0) * m(1, 1) + m(0, 0) * m(2, 2) + m(1, 1) * m(2, 2) -
                      m(0, 1) * m(0, 1) - m(0, 2) * m(0, 2) - m(1, 2) * m(1, 2),
                 c0 = m.determinant();
    double l = 0.0;
    bool converged = false;
    for (int it = 0; it < 12 && !converged; ++it) {
      const double p = ((l - c2) * l + c1) * l - c0, dp = (3.0 * l - 2.0 * c2) * l + c1;
      if (!(dp > 0.0)) break;
      const double step = p / dp;
      l -= step;
      converged = std::abs(step) <= 1e-10 * c2;
    }
    // The eigenvector: the largest cross product of two rows of m - l I (each orthogonal to it).
    const Eigen::Matrix3d r = m - l * Eigen::Matrix3d::Identity();
    const Eigen::Vector3d x[3] = {r.row(0).cross(r.row(1)), r.row(0).cross(r.row(2)),
                                  r.row(1).cross(r.row(2))};
    int best = 0;
    for (int i = 1; i < 3; ++i)
      if (x[i].squaredNorm() > x[best].squaredNorm()) best = i;
    // A cross product that small means a (nearly) double smallest root: left to Eigen.
    if (converged && x[best].squaredNorm() > 1e-16 * c2 * c2 * c2 * c2) {
      out.value = std::max(0.0, l) * scale;
      out.trace = cov.trace();  // the eigenvalues' sum, exactly
      out.vector = x[best].normalized();
      return out;
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(cov);
  out.value = std::max(0.0, es.eigenvalues()[0]);  // ascending
  out.trace = cov.trace();
  out.vector = es.eigenvectors().col(0);
  return out;
}

PointNormal normal_from_covariance(const Eigen::Matrix3d& cov, const Eigen::Vector3f& at,
                                  const Eigen::Vector3f& viewpoint) {
  PointNormal out;
  const SmallestEigen e = smallest_eigen(cov);
  Eigen::Vector3f n = e.vector.cast<float>().normalized();
  if (n.dot(viewpoint - at) < 0.0f) n = -n;  // eq. 4.6
  out.normal = n;
  out.curvature = e.trace > 0.0 ? static_cast<float>(e.value / e.trace) : 0.0f;  // eq. 4.7
  return out;
}

PointNormal normal_from(std::span<const Eigen::Vector3f> points,
                        std::span<const std::uint32_t> neighbours, const Eigen::Vector3f& at,
                        const Eigen::Vector3f& viewpoint) {
  if (neighbours.size() < 3) return {};
  return normal_from_covariance(mean_covariance(points, neighbours).cov, at, viewpoint);  // eq. 4.4-4.5
}

void compute_normals(Cloud& cloud, const NormalConfig& cfg, const Neighbours& nb) {
  // Lists shorter than k are fine when they already hold the whole cloud.
  if (cfg.radius > 0.0f || (nb.k < cfg.k && nb.k < cloud.size()) || nb.count.size() != cloud.size())
    throw Error("normals: the shared neighbour lists do not fit this cloud");
  cloud.normals.resize(cloud.size());
  cloud.curvature.resize(cloud.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const auto all = nb.of(i);
      const PointNormal pn = normal_from(cloud.points, all.first(std::min<std::size_t>(all.size(), cfg.k)),
                                         cloud.points[i], cloud.viewpoint);
      cloud.normals[i] = pn.normal;
      cloud.curvature[i] = pn.curvature;
    }
  });
}

void compute_normals(Cloud& cloud, const NormalConfig& cfg) {
  if (cfg.radius <= 0.0f && cfg.k < 3)
    throw Error("normals: k must be at least 3, got " + std::to_string(cfg.k));
  const KdTree tree(cloud.points);
  cloud.normals.assign(cloud.size(), PointNormal{}.normal);
  cloud.curvature.assign(cloud.size(), PointNormal{}.curvature);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 512), [&](const auto& r) {
    std::vector<std::uint32_t> idx(cfg.k);
    std::vector<float> d2(cfg.k);
    std::vector<std::pair<std::uint32_t, float>> hits;
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      std::size_t n = 0;
      if (cfg.radius > 0.0f) {
        tree.radius(cloud.points[i], cfg.radius, hits);
        idx.resize(hits.size());
        for (std::size_t j = 0; j < hits.size(); ++j) idx[j] = hits[j].first;
        n = hits.size();
      } else {
        n = tree.knn(cloud.points[i], cfg.k, idx.data(), d2.data());
      }
      const PointNormal pn = normal_from(cloud.points, {idx.data(), n}, cloud.points[i],
                                         cloud.viewpoint);
      cloud.normals[i] = pn.normal;
      cloud.curvature[i] = pn.curvature;
    }
  });
}

}  // namespace uwgrasp::cloud
