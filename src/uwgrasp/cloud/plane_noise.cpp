#include "uwgrasp/cloud/plane_noise.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "uwgrasp/cloud/indices.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

namespace {
// The element at size/2 of v sorted (what nth_element there gives), by a histogram of 1024
// buckets over [0, top] first: only the bucket that holds it is then selected from (a frame's
// floor bin holds 10^5 distances; nth_element over all of them took ~1 ms a bin). Values are
// in [0, top]; the bucket of a value never decreases with it, so the answer is exact. `work`
// (v.size() values) takes the bucket's values.
double median(std::span<const double> v, double top, std::span<double> work) {
  constexpr std::size_t kBuckets = 1024;
  const std::size_t k = v.size() / 2;
  const double scale = top > 0.0 ? double(kBuckets) / top : 0.0;
  const auto bucket = [&](double x) { return std::min(kBuckets - 1, std::size_t(std::max(0.0, x * scale))); };
  std::array<std::size_t, kBuckets> count{};
  for (const double x : v) ++count[bucket(x)];
  std::size_t b = 0, before = 0;
  while (before + count[b] <= k) before += count[b++];
  std::size_t n = 0;
  for (const double x : v)
    if (bucket(x) == b) work[n++] = x;
  const auto mid = work.begin() + std::ptrdiff_t(k - before);
  std::nth_element(work.begin(), mid, work.begin() + std::ptrdiff_t(n));
  return *mid;
}

// floor(range / bin): by the conversion's truncation where that is the floor (ranges are not
// negative; std::floor is a library call on x86-64 before SSE4.1), else as std::lround would.
long bin_of(double range, double bin) {
  const double x = range / bin;
  return x >= 0.0 && x < 0x1p52 ? long(x) : std::lround(std::floor(x));
}
double bin_centre(long b, double bin) { return (double(b) + 0.5) * bin; }

using Bin = NoiseScratch::Bin;

// The band's distances grouped by range bin, bins ascending, into scratch.flat and scratch.bins
// (each bin's distances contiguous, in band order): a counting sort over fixed blocks of the
// band, in parallel (a serial pass of push_backs took 0.3 ms of a frame's 150k band points). A
// bin's median does not depend on the order of its values.
void group(const std::vector<long>& bin_key, const std::vector<double>& dist,
           NoiseScratch& scratch) {
  std::vector<double>& flat = scratch.flat;
  std::vector<Bin>& bins = scratch.bins;
  flat.clear(), bins.clear();
  if (bin_key.empty()) return;
  // Plain values, not a structured binding: lambdas below use lo (clang 14 cannot capture one).
  const auto range = std::minmax_element(bin_key.begin(), bin_key.end());
  const long lo = *range.first, hi = *range.second;
  const std::size_t span = std::size_t(hi - lo + 1);
  if (hi - lo >= 4096) {  // not a frame's few metres: a map of the bins in use
    std::map<long, std::vector<double>> by_key;
    for (std::size_t j = 0; j < bin_key.size(); ++j) by_key[bin_key[j]].push_back(dist[j]);
    for (auto& [k, v] : by_key) flat.insert(flat.end(), v.begin(), v.end());
    std::size_t at = 0;
    for (auto& [k, v] : by_key)
      bins.push_back({k, std::span<const double>(flat).subspan(at, v.size())}), at += v.size();
    return;
  }
  constexpr std::size_t kBlock = std::size_t(1) << 14;
  const std::size_t blocks = (bin_key.size() + kBlock - 1) / kBlock;
  const auto block_end = [&](std::size_t c) { return std::min(bin_key.size(), (c + 1) * kBlock); };
  std::vector<std::size_t>& at = scratch.at;  // block c's count, then its start, per bin
  at.assign(blocks * span, 0);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t c) {
    for (std::size_t j = c * kBlock; j < block_end(c); ++j)
      ++at[c * span + std::size_t(bin_key[j] - lo)];
  });
  std::vector<std::size_t>& size = scratch.size;
  size.assign(span, 0);
  std::size_t start = 0;
  for (std::size_t b = 0; b < span; ++b)
    for (std::size_t c = 0; c < blocks; ++c) {
      const std::size_t n = at[c * span + b];
      at[c * span + b] = start, start += n, size[b] += n;
    }
  flat.resize(bin_key.size());
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t c) {
    for (std::size_t j = c * kBlock; j < block_end(c); ++j)
      flat[at[c * span + std::size_t(bin_key[j] - lo)]++] = dist[j];
  });
  start = 0;
  for (std::size_t b = 0; b < span; ++b) {
    if (size[b] > 0)
      bins.push_back({lo + long(b), std::span<const double>(flat).subspan(start, size[b])});
    start += size[b];
  }
}

}  // namespace

NoiseModel plane_noise(const Cloud& cloud, const Eigen::Vector4f& plane, float band, double bin,
                       std::size_t min_points) {
  NoiseScratch scratch;
  return plane_noise(cloud, plane, band, bin, min_points, scratch);
}

NoiseModel plane_noise(const Cloud& cloud, const Eigen::Vector4f& plane, float band, double bin,
                       std::size_t min_points, NoiseScratch& scratch) {
  plane_distances(cloud, plane, scratch.point_distance, scratch.point_range);
  return plane_noise(scratch.point_distance, scratch.point_range, band, bin, min_points, scratch);
}

void plane_distances(const Cloud& cloud, const Eigen::Vector4f& plane, std::vector<float>& distance,
                     std::vector<float>& range) {
  distance.resize(cloud.size()), range.resize(cloud.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Eigen::Vector3f& p = cloud.points[i];
      distance[i] = std::abs(plane.head<3>().dot(p) + plane[3]);
      range[i] = (p - cloud.viewpoint).norm();
    }
  });
}

NoiseModel plane_noise(std::span<const float> distance, std::span<const float> range, float band,
                       double bin, std::size_t min_points, NoiseScratch& scratch) {
  if (distance.size() != range.size())
    throw Error("plane_noise: " + std::to_string(distance.size()) + " distances but " +
                std::to_string(range.size()) + " ranges");
  // The band's points, their bins and distances in parallel, then one pass into per-bin lists
  // and the bins' medians in parallel (serially, a frame's floor took 2 ms of the plane stage).
  std::vector<std::uint32_t>& in_band = scratch.in_band;
  indices_where(
      distance.size(), [&](std::size_t i) { return distance[i] <= band; }, in_band);
  std::vector<long>& bin_key = scratch.bin_key;
  std::vector<double>& band_dist = scratch.distance;
  bin_key.resize(in_band.size()), band_dist.resize(in_band.size());
  tbb::parallel_for(std::size_t(0), in_band.size(), [&](std::size_t j) {
    bin_key[j] = bin_of(range[in_band[j]], bin);
    band_dist[j] = distance[in_band[j]];
  });
  group(bin_key, band_dist, scratch);
  scratch.work.resize(scratch.flat.size());  // the bins' medians select in their own slices
  const std::vector<Bin>& bins = scratch.bins;
  std::vector<double>& sigma = scratch.sigma;
  sigma.assign(bins.size(), 0.0);
  tbb::parallel_for(std::size_t(0), bins.size(), [&](std::size_t b) {
    const std::span<const double> v = bins[b].values;
    const std::size_t at = std::size_t(v.data() - scratch.flat.data());  // its slice of work
    if (v.size() >= min_points)
      sigma[b] = 1.4826 * median(v, double(band), std::span(scratch.work).subspan(at, v.size()));
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
