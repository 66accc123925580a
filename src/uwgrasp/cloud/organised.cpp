#include "uwgrasp/cloud/organised.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <limits>

#include "uwgrasp/cloud/organised_window.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

using namespace window_detail;

namespace {
// How far window_mean_distances widens a window that holds fewer than k pixels: to this many
// times its half width.
constexpr std::uint32_t kGrowth = 3;

// The sum of the square roots of the k smallest of v[0, n), n >= k, without a branch on the
// values (a window's 24 pixels, for its 10 nearest, took an insertion sort's mispredicted
// branches longer than the distances themselves): v[i] is in when fewer than k others are
// strictly smaller. Values tied at the k-th smallest are then all in; the surplus are equal to
// the largest one in, and are taken off again.
template <std::size_t N = 0>
double sum_of_smallest_roots(const float* v, std::size_t n, std::size_t k) {
  if constexpr (N > 0) n = N;  // a whole 5 x 5 window: loops of known length vectorise
  // 32-bit counts: twice the lanes of 64-bit ones; a window has at most 15 x 15 - 1 pixels.
  std::array<std::uint32_t, (N > 0 ? N : 224)> smaller{};
  for (std::size_t e = 0; e < n; ++e)
    for (std::size_t i = 0; i < n; ++i) smaller[i] += v[e] < v[i];
  double sum = 0.0;
  std::size_t in = 0;
  float top = 0.0f;
  for (std::size_t i = 0; i < n; ++i) {
    const bool take = smaller[i] < k;
    sum += take ? double(std::sqrt(v[i])) : 0.0;
    in += take;
    top = take ? std::max(top, v[i]) : top;
  }
  return sum - double(in - k) * double(std::sqrt(top));
}

// Offers d2 to best[0, size), the k smallest so far in ascending order (room for k).
void offer(float* best, std::size_t& size, std::size_t k, float d2) {
  if (size == k && d2 >= best[size - 1]) return;
  if (size == k) --size;
  float* const at = std::upper_bound(best, best + size, d2);
  std::move_backward(at, best + size, best + size + 1);
  *at = d2, ++size;
}
}  // namespace

PixelMap pixel_map(std::uint32_t width, std::uint32_t height, std::vector<std::uint32_t> pixels) {
  PixelMap m;
  m.width = width, m.height = height;
  m.slot.assign(std::size_t(width) * height, -1);
  const auto outside = std::find_if(pixels.begin(), pixels.end(), [&](std::uint32_t p) { return p >= m.slot.size(); });
  if (outside != pixels.end())
    throw Error("pixel_map: pixel " + std::to_string(*outside) + " outside the frame");
  tbb::parallel_for(std::size_t(0), pixels.size(), [&](std::size_t j) { m.slot[pixels[j]] = static_cast<std::int32_t>(j); });
  m.pixel = std::move(pixels);
  return m;
}

Neighbours window_neighbours(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                             const OrganisedConfig& cfg, const Eigen::Vector3f& viewpoint) {
  Neighbours nb;
  WindowScratch scratch;
  window_neighbours(points, map, cfg, viewpoint, nb, scratch);
  return nb;
}

void window_neighbours(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                       const OrganisedConfig& cfg, const Eigen::Vector3f& viewpoint, Neighbours& nb,
                       WindowScratch& scratch) {
  check_window(cfg.half_window);
  const std::span<const float> range = ranges(points, viewpoint, scratch.range);
  const WindowTable table(map.width, cfg.half_window);
  nb.k = std::size_t(2 * cfg.half_window + 1) * (2 * cfg.half_window + 1), nb.window = true;
  nb.indices.resize(points.size() * nb.k), nb.sq_dists.resize(points.size() * nb.k);
  nb.count.resize(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024), [&](const auto& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j)
      nb.count[j] = std::uint32_t(window_list(points, map, table, cfg.depth_change, range, j,
                                              &nb.indices[j * nb.k], &nb.sq_dists[j * nb.k]));
  });
}

std::vector<float> window_mean_distances(std::span<const Eigen::Vector3f> points,
                                         const PixelMap& map, std::uint32_t half_window,
                                         std::uint32_t k) {
  std::vector<float> mean;
  window_mean_distances(points, map, half_window, k, mean);
  return mean;
}

void window_mean_distances(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                           std::uint32_t half_window, std::uint32_t k, std::vector<float>& mean) {
  check_window(half_window);
  k = std::max<std::uint32_t>(k, 1);
  const int widest = int(kGrowth * half_window);
  const WindowTable table(map.width, half_window);
  mean.resize(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024), [&](const auto& r) {
    std::array<float, kMaxWindow> d2;  // the window's pixels (check_window: at most 224)
    // The k nearest next to holes: on the stack, or for a k above a window's pixels a list.
    std::array<float, kMaxWindow> nearest;
    std::vector<float> many(k > kMaxWindow ? k : 0);
    float* const best = k > kMaxWindow ? many.data() : nearest.data();
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const Eigen::Vector3f pj = points[j];
      std::size_t n = 0;
      for_each_window_pixel(map, table, j,
                            [&](std::size_t s, int) { d2[n++] = (points[s] - pj).squaredNorm(); });
      if (n >= k) {
        const double sum = n == 24 ? sum_of_smallest_roots<24>(d2.data(), n, k)
                                   : sum_of_smallest_roots(d2.data(), n, k);
        mean[j] = float(sum / double(k));
        continue;
      }
      // Fewer than k pixels in play: whole rings more, next to a hole or a removed plane, where
      // a k-d tree search finds the k nearest further out in the image.
      std::size_t size = n;  // n < k
      std::copy_n(d2.begin(), n, best);
      std::sort(best, best + size);
      for (int ring = int(half_window) + 1; ring <= widest && n < k; ++ring)
        for_each_ring_pixel(map, j, ring, [&](std::size_t s) {
          ++n, offer(best, size, k, (points[s] - pj).squaredNorm());
        });
      if (size == 0) {
        mean[j] = std::numeric_limits<float>::infinity();
        continue;
      }
      double sum = 0.0;
      for (std::size_t b = 0; b < size; ++b) sum += std::sqrt(best[b]);
      mean[j] = float(sum / double(size));
    }
  });
}

}  // namespace uwgrasp::cloud
