#include "uwgrasp/grasp/symmetry_search.hpp"

#include <Eigen/Eigenvalues>

namespace uwgrasp::grasp::symmetry_detail {

Scored best_offset(std::span<const V3> sample, const V3& n, const SceneView& view, float lo, float hi,
                   float step, float tolerance, const SymmetryConfig& cfg) {
  const Eigen::Matrix3f R = view.camera_from_level.linear().cast<float>();
  const V3 t = view.camera_from_level.translation().cast<float>();
  // Each thread's buffers, reused: the coarse grid alone asks for thousands of offset searches.
  thread_local std::vector<V3> base, level;
  thread_local std::vector<MirrorPlane> tried;
  base.resize(sample.size()), level.resize(sample.size()), tried.clear();
  for (std::size_t i = 0; i < sample.size(); ++i) {
    level[i] = sample[i] - 2.0f * n.dot(sample[i]) * n;
    base[i] = R * level[i] + t;
  }
  const V3 u = 2.0f * (R * n), w = 2.0f * n;
  const float size = float(sample.size());
  const int limit = int(std::floor(cfg.max_violations * size));
  for (int k = 0; lo + float(k) * step <= hi + 1e-6f; ++k) {
    const float d = lo + float(k) * step;
    int support = 0, violations = 0;
    for (std::size_t i = 0; i < base.size() && violations <= limit; ++i) {
      const Seen s = classify_camera(view, base[i] + d * u, level[i] + d * w, tolerance);
      support += s == Seen::support, violations += s == Seen::violation;
    }
    // Past the violation limit the plane cannot be kept: the rest of the sample is not asked.
    const float score = violations > limit ? -std::numeric_limits<float>::infinity()
                                           : (float(support) - cfg.violation_weight * float(violations)) / size;
    tried.push_back({n, d, float(support) / size, float(violations) / size, score});
  }
  std::size_t best = 0;
  for (std::size_t k = 1; k < tried.size(); ++k)
    if (tried[k].score > tried[best].score) best = k;
  if (tried.empty() || !std::isfinite(tried[best].score)) return {};
  const float near_best = tried[best].score - 1.0f / size;  // within one point of the best
  std::size_t first = best, last = best;
  while (first > 0 && tried[first - 1].score >= near_best) --first;
  while (last + 1 < tried.size() && tried[last + 1].score >= near_best) ++last;
  return {tried[(first + last) / 2], true};
}

MirrorPlane align(MirrorPlane plane, std::span<const V3> sample, const cloud::KdTree& seen,
                  const SceneView& view, float tolerance) {
  for (int iteration = 0; iteration < 3; ++iteration) {
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    Eigen::Vector3d middle = Eigen::Vector3d::Zero();
    double weight = 0.0;
    std::size_t pairs = 0;
    for (const V3& p : sample) {
      const V3 m = plane.mirror(p);
      if (classify(view, m, tolerance) != Seen::support) continue;
      std::uint32_t index = 0;
      float d2 = 0.0f;
      if (seen.knn(m, 1, &index, &d2) == 0 || d2 > 4.0f * tolerance * tolerance) continue;
      const V3 q = seen.points()[index];
      const Eigen::Vector3d diff = (p - q).cast<double>();
      if (diff.norm() < 4.0 * tolerance) continue;  // too near the plane to tell its direction
      const double w = diff.squaredNorm();
      scatter += diff * diff.transpose();
      middle += w * (0.5f * (p + q)).cast<double>();
      weight += w, ++pairs;
    }
    if (pairs < 10) return plane;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(scatter);
    V3 n = es.eigenvectors().col(2).cast<float>().normalized();
    if (n.dot(plane.normal) < 0.0f) n = -n;
    if (n.dot(plane.normal) < std::cos(0.2f)) return plane;  // the pairs disagree with the plane
    plane.normal = n;
    plane.offset = n.dot((middle / weight).cast<float>());
  }
  return plane;
}

}  // namespace uwgrasp::grasp::symmetry_detail
