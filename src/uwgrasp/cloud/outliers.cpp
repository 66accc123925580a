#include "uwgrasp/cloud/outliers.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

namespace {
// Mean distance to the neighbours after the first (the query point finds itself first).
float mean_after_first(std::span<const float> d2) {
  double sum = 0.0;
  for (std::size_t j = 1; j < d2.size(); ++j) sum += std::sqrt(d2[j]);
  return d2.size() > 1 ? static_cast<float>(sum / static_cast<double>(d2.size() - 1)) : 0.0f;
}

bool keeps_all(const Cloud& in, const OutlierConfig& cfg) {
  return in.size() <= cfg.k || cfg.k == 0;
}

Filtered unchanged(const Cloud& in) {
  Filtered all{in, {}};
  all.indices.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) all.indices[i] = static_cast<std::uint32_t>(i);
  make_unorganised(all.cloud);
  return all;
}
}  // namespace

Filtered remove_outliers_by(const Cloud& in, const OutlierConfig& cfg,
                            const std::vector<float>& mean) {
  if (mean.size() != in.size()) throw Error("outliers: the mean distances do not fit this cloud");
  std::vector<char> keep;
  outlier_mask(cfg, mean, keep);
  return keep_if(in, keep);
}

void outlier_mask(const OutlierConfig& cfg, const std::vector<float>& mean,
                  std::vector<char>& keep) {
  // mu and the sample standard deviation over the points, summed in order (deterministic).
  double sum = 0.0, sq_sum = 0.0, n = 0.0;
  for (float m : mean)
    if (std::isfinite(m)) sum += m, sq_sum += static_cast<double>(m) * m, n += 1.0;
  const double mu = n > 0.0 ? sum / n : 0.0;
  const double var = n > 1.0 ? std::max(0.0, (sq_sum - sum * sum / n) / (n - 1.0)) : 0.0;
  const double threshold = mu + cfg.std_mul * std::sqrt(var);
  keep.resize(mean.size());
  for (std::size_t i = 0; i < mean.size(); ++i) keep[i] = mean[i] <= threshold;
}

std::vector<float> mean_neighbour_distances(const Cloud& in, std::uint32_t k) {
  const KdTree tree(in.points);
  std::vector<float> mean(in.size(), 0.0f);
  const std::size_t kk = k + 1;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.size(), 512), [&](const auto& r) {
    std::vector<std::uint32_t> idx(kk);
    std::vector<float> d2(kk);
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      mean[i] = mean_after_first({d2.data(), tree.knn(in.points[i], kk, idx.data(), d2.data())});
  });
  return mean;
}

Filtered remove_outliers(const Cloud& in, const OutlierConfig& cfg) {
  if (keeps_all(in, cfg)) return unchanged(in);
  return remove_outliers_by(in, cfg, mean_neighbour_distances(in, cfg.k));
}

Filtered remove_outliers(const Cloud& in, const OutlierConfig& cfg, const Neighbours& nb) {
  if (keeps_all(in, cfg)) return unchanged(in);
  if (nb.count.size() != in.size() || nb.window || nb.k < std::size_t{cfg.k} + 1)
    throw Error("outliers: the shared neighbour lists do not fit this cloud");
  std::vector<float> mean(in.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::size_t n = std::min<std::size_t>(nb.count[i], cfg.k + 1);
      mean[i] = mean_after_first(nb.dists_of(i).first(n));
    }
  });
  return remove_outliers_by(in, cfg, mean);
}

}  // namespace uwgrasp::cloud
