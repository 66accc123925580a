#include "uwgrasp/cloud/plane_noise.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "uwgrasp/cloud/indices.hpp"

namespace uwgrasp::cloud {

namespace {
// The element at size/2 of v sorted (what nth_element there gives), by a histogram of 1024
// buckets over [0, top] first: only the bucket that holds it is then selected from (a frame's
// floor bin holds 10^5 distances; nth_element over all of them took ~1 ms a bin). Values are
// in [0, top]; the bucket of a value never decreases with it, so the answer is exact.
double median(std::vector<double>& v, double top) {
  constexpr std::size_t kBuckets = 1024;
  const std::size_t k = v.size() / 2;
  const double scale = top > 0.0 ? double(kBuckets) / top : 0.0;
  const auto bucket = [&](double x) { return std::min(kBuckets - 1, std::size_t(std::max(0.0, x * scale))); };
  std::array<std::size_t, kBuckets> count{};
  for (const double x : v) ++count[bucket(x)];
  std::size_t b = 0, before = 0;
  while (before + count[b] <= k) before += count[b++];
  std::vector<double> in;
  in.reserve(count[b]);
  for (const double x : v)
    if (bucket(x) == b) in.push_back(x);
  const auto mid = in.begin() + std::ptrdiff_t(k - before);
  std::nth_element(in.begin(), mid, in.end());
  return *mid;
}

long bin_of(double range, double bin) { return std::lround(std::floor(range / bin)); }
double bin_centre(long b, double bin) { return (double(b) + 0.5) * bin; }

// A range bin: its index and the distances collected in it.
struct Bin {
  long key = 0;
  std::vector<double> values;
};

// The band's distances grouped by range bin, bins ascending. A bin's median does not depend on
// the order of its values.
std::vector<Bin> group(const std::vector<long>& bin_key, const std::vector<double>& dist) {
  std::vector<Bin> bins;
  if (bin_key.empty()) return bins;
  const auto [lo, hi] = std::minmax_element(bin_key.begin(), bin_key.end());
  if (*hi - *lo >= 4096) {  // not a frame's few metres: a map of the bins in use
    std::map<long, std::vector<double>> by_key;
    for (std::size_t j = 0; j < bin_key.size(); ++j) by_key[bin_key[j]].push_back(dist[j]);
    for (auto& [k, v] : by_key) bins.push_back({k, std::move(v)});
    return bins;
  }
  std::vector<std::size_t> size(std::size_t(*hi - *lo + 1), 0);
  for (const long k : bin_key) ++size[std::size_t(k - *lo)];
  std::vector<std::size_t> slot(size.size());
  for (std::size_t b = 0; b < size.size(); ++b) {
    if (size[b] == 0) continue;
    slot[b] = bins.size();
    bins.push_back({*lo + long(b), {}});
    bins.back().values.reserve(size[b]);
  }
  for (std::size_t j = 0; j < bin_key.size(); ++j) bins[slot[std::size_t(bin_key[j] - *lo)]].values.push_back(dist[j]);
  return bins;
}

}  // namespace

NoiseModel plane_noise(const Cloud& cloud, const Eigen::Vector4f& plane, float band, double bin,
                       std::size_t min_points) {
  const auto dist = [&](std::size_t i) { return std::abs(double(plane.head<3>().dot(cloud.points[i]) + plane[3])); };
  // The band's points, their bins and distances in parallel, then one pass into per-bin lists
  // and the bins' medians in parallel (serially, a frame's floor took 2 ms of the plane stage).
  const std::vector<std::uint32_t> in_band = indices_where(cloud.size(), [&](std::size_t i) { return dist(i) <= band; });
  std::vector<long> bin_key(in_band.size());
  std::vector<double> band_dist(in_band.size());
  tbb::parallel_for(std::size_t(0), in_band.size(), [&](std::size_t j) {
    bin_key[j] = bin_of((cloud.points[in_band[j]] - cloud.viewpoint).norm(), bin);
    band_dist[j] = dist(in_band[j]);
  });
  std::vector<Bin> bins = group(bin_key, band_dist);
  std::vector<double> sigma(bins.size(), 0.0);
  tbb::parallel_for(std::size_t(0), bins.size(), [&](std::size_t b) {
    if (bins[b].values.size() >= min_points) sigma[b] = 1.4826 * median(bins[b].values, double(band));
  });
  // sigma_b = sigma0 + sigma_k r_b^2, least squares over the bins (weighted equally), in order.
  Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  NoiseModel model;
  for (std::size_t k = 0; k < bins.size(); ++k) {
    if (bins[k].values.size() < min_points) continue;
    const double r = bin_centre(bins[k].key, bin);
    const Eigen::Vector2d x(1.0, r * r);
    a += x * x.transpose();
    b += x * sigma[k];
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
