#include "uwgrasp/cloud/plane_noise.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace uwgrasp::cloud {

namespace {
double median(std::vector<double>& v) {
  const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// Per range bin (key: bin index), the values collected in it.
using Bins = std::map<long, std::vector<double>>;

long bin_of(double range, double bin) { return std::lround(std::floor(range / bin)); }
double bin_centre(long b, double bin) { return (double(b) + 0.5) * bin; }

}  // namespace

NoiseModel plane_noise(const Cloud& cloud, const Eigen::Vector4f& plane, float band, double bin,
                       std::size_t min_points) {
  Bins bins;
  for (const Eigen::Vector3f& p : cloud.points) {
    const double dist = std::abs(double(plane.head<3>().dot(p) + plane[3]));
    if (dist <= band) bins[bin_of((p - cloud.viewpoint).norm(), bin)].push_back(dist);
  }
  // sigma_b = sigma0 + sigma_k r_b^2, least squares over the bins (weighted equally).
  Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  NoiseModel model;
  for (auto& [key, v] : bins) {
    if (v.size() < min_points) continue;
    const double r = bin_centre(key, bin), sigma = 1.4826 * median(v);
    const Eigen::Vector2d x(1.0, r * r);
    a += x * x.transpose();
    b += x * sigma;
    ++model.bins;
  }
  if (model.bins < 2 || std::abs(a.determinant()) < 1e-12) return model;
  const Eigen::Vector2d s = a.ldlt().solve(b);
  model.found = true;
  model.sigma0 = std::max(0.0, s[0]);
  model.sigma_k = std::max(0.0, s[1]);
  return model;
}

}  // namespace uwgrasp::cloud
