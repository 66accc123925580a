#include "uwgrasp/cloud/ransac.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <utility>

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <limits>

#include "uwgrasp/cloud/indices.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::cloud {

namespace {
constexpr std::uint32_t kBatch = 8;  // hypotheses scored in one pass over the points

using Counts = std::array<std::uint32_t, kBatch>;

// Inlier counts of up to kBatch planes in one parallel pass (integer sums: deterministic).
Counts count_inliers(const Cloud& in, const std::array<Eigen::Vector4f, kBatch>& planes,
                     std::uint32_t nplanes, float tol) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, in.size(), 1 << 13), Counts{},
      [&](const auto& r, Counts c) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const Eigen::Vector3f& p = in.points[i];
          for (std::uint32_t h = 0; h < nplanes; ++h) {
            const auto& m = planes[h];
            c[h] += std::abs(m[0] * p.x() + m[1] * p.y() + m[2] * p.z() + m[3]) <= tol;
          }
        }
        return c;
      },
      [](Counts a, const Counts& b) {
        for (std::uint32_t h = 0; h < kBatch; ++h) a[h] += b[h];
        return a;
      });
}

// Plane through three random distinct points of hypothesis i; false if they are collinear.
bool hypothesis(const Cloud& in, std::uint64_t seed, std::uint32_t i, Eigen::Vector4f& plane) {
  Rng rng(seed, i);
  const std::uint64_t n = in.size();
  const std::uint64_t a = rng.below(n);
  std::uint64_t b = rng.below(n), c = rng.below(n);
  for (int t = 0; t < 16 && (b == a); ++t) b = rng.below(n);
  for (int t = 0; t < 16 && (c == a || c == b); ++t) c = rng.below(n);
  const Eigen::Vector3f p0 = in.points[a], u = in.points[b] - p0, v = in.points[c] - p0;
  Eigen::Vector3f nrm = u.cross(v);
  const float len = nrm.norm();
  if (!(len > 1e-12f * std::max(1.0f, u.squaredNorm() + v.squaredNorm()))) return false;
  nrm /= len;
  plane = Eigen::Vector4f(nrm.x(), nrm.y(), nrm.z(), -nrm.dot(p0));
  return true;
}

// Whether p lies within tol of the plane m: the inlier test of the selection and the refit.
bool within(const Eigen::Vector4f& m, const Eigen::Vector3f& p, float tol) {
  return std::abs(m.head<3>().dot(p) + m[3]) <= tol;
}

void select_inliers(const Cloud& in, const Eigen::Vector4f& m, float tol,
                    std::vector<std::uint32_t>& out) {
  indices_where(
      in.size(), [&](std::size_t i) { return within(m, in.points[i], tol); }, out);
}
}  // namespace

double ransac_iterations(double p, double w, int n) {
  const double wn = std::pow(w, n);
  if (wn >= 1.0) return 1.0;
  if (wn <= 0.0) return std::numeric_limits<double>::infinity();
  return std::max(1.0, std::ceil(std::log(1.0 - p) / std::log(1.0 - wn)));
}

Eigen::Vector4f least_squares_plane(const Cloud& in, const Eigen::Vector4f& plane, float tol) {
  // Two passes over the cloud (the mean, then the covariance about it, eq. 4.4), each summed in
  // fixed blocks combined in a fixed order: the same result whatever the thread count, and no
  // list of a frame's 10^5 inliers to build first (select + a serial covariance took 0.6 ms).
  const auto inlier = [&](const Eigen::Vector3f& p) { return within(plane, p, tol); };
  const tbb::blocked_range<std::size_t> all(0, in.size(), 1 << 13);
  using Sum = std::pair<Eigen::Vector3d, std::size_t>;
  const Sum s = tbb::parallel_deterministic_reduce(
      all, Sum{Eigen::Vector3d::Zero(), 0},
      [&](const auto& r, Sum acc) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
          if (inlier(in.points[i])) acc.first += in.points[i].cast<double>(), ++acc.second;
        return acc;
      },
      [](const Sum& a, const Sum& b) { return Sum{a.first + b.first, a.second + b.second}; });
  if (s.second < 3) return plane;
  const Eigen::Vector3d mean = s.first / double(s.second);
  const Eigen::Matrix3d cov = tbb::parallel_deterministic_reduce(
      all, Eigen::Matrix3d::Zero().eval(),
      [&](const auto& r, Eigen::Matrix3d acc) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
          if (inlier(in.points[i])) {
            const Eigen::Vector3d d = in.points[i].cast<double>() - mean;
            acc.noalias() += d * d.transpose();
          }
        return acc;
      },
      [](const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return (a + b).eval(); });
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov / double(s.second));
  const Eigen::Vector3d n = es.eigenvectors().col(0);
  return Eigen::Vector4d(n.x(), n.y(), n.z(), -n.dot(mean)).cast<float>();
}

PlaneResult fit_plane(const Cloud& in, const PlaneConfig& cfg, std::uint64_t seed) {
  PlaneResult res;
  fit_plane(in, cfg, seed, res);
  return res;
}

void fit_plane(const Cloud& in, const PlaneConfig& cfg, std::uint64_t seed, PlaneResult& res) {
  res.found = false, res.coefficients.setZero(), res.iterations = 0;
  res.inliers.clear();
  if (in.size() < 3) return;
  const double n = static_cast<double>(in.size());
  std::uint32_t budget = cfg.max_iterations, best_count = 0;
  Eigen::Vector4f best = Eigen::Vector4f::Zero();
  std::uint32_t drawn = 0;
  while (drawn < budget) {
    std::array<Eigen::Vector4f, kBatch> planes{};
    std::array<bool, kBatch> valid{};
    const std::uint32_t nb = std::min(kBatch, budget - drawn);
    for (std::uint32_t h = 0; h < nb; ++h) valid[h] = hypothesis(in, seed, drawn + h, planes[h]);
    const Counts counts = count_inliers(in, planes, nb, cfg.distance);
    // Replay the batch in order, exactly as a sequential RANSAC would have run it.
    for (std::uint32_t h = 0; h < nb && drawn < budget; ++h, ++drawn) {
      if (!valid[h] || counts[h] <= best_count) continue;
      best_count = counts[h];
      best = planes[h];
      const double k = ransac_iterations(cfg.probability, best_count / n);
      budget = static_cast<std::uint32_t>(std::min<double>(cfg.max_iterations, k));
    }
  }
  res.iterations = drawn;
  if (best_count < 3 || best_count < cfg.min_inlier_ratio * n) return;
  res.found = true;
  res.coefficients = best;
  if (cfg.refine) res.coefficients = least_squares_plane(in, best, cfg.distance);
  select_inliers(in, res.coefficients, cfg.distance, res.inliers);
  // Orient the normal towards the viewpoint (eq. 4.6) so the sign is reproducible.
  if (res.coefficients.head<3>().dot(in.viewpoint) + res.coefficients[3] < 0.0f)
    res.coefficients = -res.coefficients;
}

}  // namespace uwgrasp::cloud
