#include "uwgrasp/cloud/normals.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <vector>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

PointNormal normal_from_covariance(const Eigen::Matrix3d& cov, const Eigen::Vector3f& at,
                                  const Eigen::Vector3f& viewpoint) {
  PointNormal out;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(cov);
  const Eigen::Vector3d l = es.eigenvalues().cwiseMax(0.0);  // ascending
  Eigen::Vector3f n = es.eigenvectors().col(0).cast<float>().normalized();
  if (n.dot(viewpoint - at) < 0.0f) n = -n;  // eq. 4.6
  const double sum = l.sum();
  out.normal = n;
  out.curvature = sum > 0.0 ? static_cast<float>(l[0] / sum) : 0.0f;  // eq. 4.7
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
