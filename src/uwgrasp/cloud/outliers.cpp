#include "uwgrasp/cloud/outliers.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "uwgrasp/cloud/kdtree.hpp"

namespace uwgrasp::cloud {

std::vector<float> mean_neighbour_distances(const Cloud& in, std::uint32_t k) {
  const KdTree tree(in.points);
  std::vector<float> mean(in.size(), 0.0f);
  const std::size_t kk = k + 1;  // the query point finds itself first
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.size(), 512), [&](const auto& r) {
    std::vector<std::uint32_t> idx(kk);
    std::vector<float> d2(kk);
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::size_t n = tree.knn(in.points[i], kk, idx.data(), d2.data());
      double sum = 0.0;
      for (std::size_t j = 1; j < n; ++j) sum += std::sqrt(d2[j]);
      mean[i] = n > 1 ? static_cast<float>(sum / static_cast<double>(n - 1)) : 0.0f;
    }
  });
  return mean;
}

Filtered remove_outliers(const Cloud& in, const OutlierConfig& cfg) {
  if (in.size() <= cfg.k || cfg.k == 0) {
    Filtered all{in, {}};
    all.indices.resize(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) all.indices[i] = static_cast<std::uint32_t>(i);
    make_unorganised(all.cloud);
    return all;
  }
  const std::vector<float> mean = mean_neighbour_distances(in, cfg.k);
  // mu and the sample standard deviation over all points, summed in order (deterministic).
  double sum = 0.0, sq_sum = 0.0;
  for (float m : mean) {
    sum += m;
    sq_sum += static_cast<double>(m) * m;
  }
  const double n = static_cast<double>(mean.size());
  const double mu = sum / n;
  const double var = std::max(0.0, (sq_sum - sum * sum / n) / (n - 1.0));
  const double threshold = mu + cfg.std_mul * std::sqrt(var);
  std::vector<char> keep(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) keep[i] = mean[i] <= threshold;
  return keep_if(in, keep);
}

}  // namespace uwgrasp::cloud
