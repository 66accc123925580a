#pragma once
// Statistical outlier removal (thesis 4.1.3, Rusu et al. 2008).
#include "uwgrasp/cloud/filters.hpp"
#include "uwgrasp/cloud/kdtree.hpp"

namespace uwgrasp::cloud {

struct OutlierConfig {
  bool enabled = true;
  std::uint32_t k = 10;   // neighbours whose mean distance describes a point
  // threshold mu + std_mul * sigma. The thesis uses mu + sigma, which removes the sparse points of
  // faces seen at a grazing angle (a box's top seen from its front), not only noise: 3 keeps them.
  double std_mul = 3.0;
};

// Removes points whose mean distance to their k nearest neighbours exceeds mu + std_mul*sigma,
// where mu and sigma are the mean and (sample) standard deviation of that distance over the
// cloud. Points must be finite. A cloud with <= k points is returned unchanged.
Filtered remove_outliers(const Cloud& in, const OutlierConfig& cfg);
// The same from neighbour lists already found for this cloud (knn_all over its own points with
// nb.k >= cfg.k + 1, each list holding the point itself first): the same points are removed.

// The same from each point's mean neighbour distance, found by the caller (e.g. over an
// organised frame's pixel windows); an infinite mean (no neighbour at all) is removed and left
// out of mu and sigma.
Filtered remove_outliers_by(const Cloud& in, const OutlierConfig& cfg,
                            const std::vector<float>& mean);
// Which points remove_outliers_by keeps: keep[i] = 1, into `keep` (its capacity reused).
void outlier_mask(const OutlierConfig& cfg, const std::vector<float>& mean,
                  std::vector<char>& keep);
Filtered remove_outliers(const Cloud& in, const OutlierConfig& cfg, const Neighbours& nb);

// The per-point mean neighbour distances (exposed for tests and diagnostics).
std::vector<float> mean_neighbour_distances(const Cloud& in, std::uint32_t k);

}  // namespace uwgrasp::cloud
