#include "uwgrasp/cloud/organised.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "uwgrasp/cloud/organised_window.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

using namespace window_detail;

namespace {
// How far window_mean_distances widens a window that holds fewer than k pixels: to this many
// times its half width.
constexpr std::uint32_t kGrowth = 3;
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
  check_window(cfg.half_window);
  const Ranges range(points, viewpoint);
  const WindowTable table(map.width, cfg.half_window);
  Neighbours nb;
  nb.k = std::size_t(2 * cfg.half_window + 1) * (2 * cfg.half_window + 1), nb.window = true;
  nb.indices.resize(points.size() * nb.k), nb.sq_dists.resize(points.size() * nb.k);
  nb.count.resize(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024), [&](const auto& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j)
      nb.count[j] = std::uint32_t(window_list(points, map, table, cfg.depth_change, range, j,
                                              &nb.indices[j * nb.k], &nb.sq_dists[j * nb.k]));
  });
  return nb;
}

std::vector<float> window_mean_distances(std::span<const Eigen::Vector3f> points,
                                         const PixelMap& map, std::uint32_t half_window,
                                         std::uint32_t k) {
  check_window(half_window);
  const int widest = int(kGrowth * half_window);
  const WindowTable table(map.width, half_window);
  std::vector<float> mean(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024), [&](const auto& r) {
    std::vector<float> best(std::max<std::uint32_t>(k, 1));  // the k smallest so far, ascending
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      std::size_t n = 0, m = 0;
      // Kept in order by insertion as they come: a window's 24 pixels, for its 10 nearest, took
      // nth_element longer than the distances themselves (outlier statistic 4.1 -> 3.3 ms on
      // mOSD_learn0).
      const auto offer = [&](float d2) {
        ++n;
        if (m == best.size() && d2 >= best.back()) return;
        std::size_t i = m < best.size() ? m++ : m - 1;
        for (; i > 0 && best[i - 1] > d2; --i) best[i] = best[i - 1];
        best[i] = d2;
      };
      // The window, then whole rings more while it holds fewer than k pixels in play: next to a
      // hole or a removed plane the k nearest points lie further out in the image, where a k-d
      // tree search finds them.
      const Eigen::Vector3f pj = points[j];
      for_each_window_pixel(map, table, j, [&](std::size_t s, int) { offer((points[s] - pj).squaredNorm()); });
      for (int ring = int(half_window) + 1; ring <= widest && n < k; ++ring)
        for_each_ring_pixel(map, j, ring, [&](std::size_t s) { offer((points[s] - pj).squaredNorm()); });
      if (m == 0) {
        mean[j] = std::numeric_limits<float>::infinity();
        continue;
      }
      double sum = 0.0;
      for (std::size_t e = 0; e < m; ++e) sum += std::sqrt(best[e]);
      mean[j] = float(sum / double(m));
    }
  });
  return mean;
}

}  // namespace uwgrasp::cloud
