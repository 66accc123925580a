#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/grasp/shape.hpp"

// The seen surface's noise: a statistic of the camera's points, kept apart from building the grid.
namespace uwgrasp::grasp {

float surface_noise(std::span<const Eigen::Vector3f> points, std::size_t k, std::size_t samples,
                    const cloud::KdTree* shared) {
  if (points.size() <= k) return 0.0f;
  std::optional<cloud::KdTree> own;
  const cloud::KdTree& tree = shared ? *shared : own.emplace(points);
  const std::size_t step = std::max<std::size_t>(1, points.size() / samples);
  std::vector<float> rms((points.size() + step - 1) / step);
  // Ranges of at least 64 samples: the lists are a range's, not a sample's; on the stack for
  // the k the shape asks (12), so a stream of frames does not ask the allocator for them.
  constexpr std::size_t kOnStack = 32;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rms.size(), 64), [&](const auto& r) {
    std::uint32_t idx_stack[kOnStack];
    float d2_stack[kOnStack];
    std::vector<std::uint32_t> idx_heap(k > kOnStack ? k : 0);
    std::vector<float> d2_heap(idx_heap.size());
    std::uint32_t* idx = k > kOnStack ? idx_heap.data() : idx_stack;
    float* d2 = k > kOnStack ? d2_heap.data() : d2_stack;
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      const std::size_t n = tree.knn(points[s * step], k, idx, d2);
      const MeanCovariance mc = mean_covariance(points, std::span<const std::uint32_t>(idx, n));
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(mc.cov, Eigen::EigenvaluesOnly);
      rms[s] = float(std::sqrt(std::max(0.0, es.eigenvalues()[0])));
    }
  });
  std::nth_element(rms.begin(), rms.begin() + std::ptrdiff_t(rms.size() / 2), rms.end());
  return rms[rms.size() / 2];
}

}  // namespace uwgrasp::grasp
