#pragma once
// The sensor's depth noise, measured on the seafloor (not in the thesis, whose 1 cm plane
// tolerance, 4.1.4, suits a perfect sensor). The seafloor is the one surface whose shape is
// known - the fitted plane - and it is seen over a wide span of ranges, so its points' distances
// from the plane, per range, are the noise: a robust spread per range bin, then
// sigma(r) = sigma0 + sigma_k r^2, the law of structured-light and stereo depth error (Nguyen,
// Izadi & Lovell 2012). The spread is along the plane's normal, the direction that decides which
// points are seafloor. A noisy sensor leaves a fuzz of seafloor points outside a fixed tolerance,
// and the grasp check then finds "obstacles" around every object's foot; the inlier band follows
// the measured noise instead.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::cloud {

struct NoiseModel {
  bool found = false;
  double sigma0 = 0.0, sigma_k = 0.0;  // sigma(r) = sigma0 + sigma_k r^2, m and 1/m
  int bins = 0;                        // range bins the fit used
  double at(double range) const { return sigma0 + sigma_k * range * range; }
};

// The noise of the points near `plane` (n.p + d = 0, |n| = 1), ranges from cloud.viewpoint: in
// bins of `bin` m, 1.4826 x the median distance from the plane of the points within `band` m of
// it (the seafloor's points are most of each bin's, the objects' feet few), then the
// least-squares law over the bins of at least `min_points`, clamped to sigma0, sigma_k >= 0.
// Not found with fewer than two bins.
constexpr double kNoiseBin = 0.25;  // m
constexpr std::size_t kNoiseMinPoints = 200;
NoiseModel plane_noise(const Cloud& cloud, const Eigen::Vector4f& plane, float band,
                       double bin = kNoiseBin, std::size_t min_points = kNoiseMinPoints);

// Its buffers, for a caller that keeps them over a stream of frames (workspace.hpp): the band's
// points, their range bins and distances, grouped by bin.
struct NoiseScratch {
  struct Bin {
    long key = 0;
    std::span<const double> values;
  };
  std::vector<float> point_distance, point_range;  // plane_distances' output, per point
  std::vector<std::uint32_t> in_band;
  std::vector<long> bin_key;
  std::vector<double> distance, flat, work, sigma;
  std::vector<std::size_t> at, size;
  std::vector<Bin> bins;
};
NoiseModel plane_noise(const Cloud& cloud, const Eigen::Vector4f& plane, float band, double bin,
                       std::size_t min_points, NoiseScratch& scratch);

// Each point's distance from `plane` and range from cloud.viewpoint, in parallel: what
// plane_noise measures, for a caller that measures more than once and then tests the points
// against the model (the plane stage: three passes over a frame computed them again each time).
void plane_distances(const Cloud& cloud, const Eigen::Vector4f& plane, std::vector<float>& distance,
                     std::vector<float>& range);
// plane_noise from plane_distances' output.
NoiseModel plane_noise(std::span<const float> distance, std::span<const float> range, float band,
                       double bin, std::size_t min_points, NoiseScratch& scratch);

}  // namespace uwgrasp::cloud
