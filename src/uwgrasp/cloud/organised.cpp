#include "uwgrasp/cloud/organised.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

namespace {
// How far window_mean_distances widens a window that holds fewer than k pixels: to this many
// times its half width.
constexpr std::uint32_t kGrowth = 3;

// Calls f(s) for every in-play pixel s at Chebyshev distance `ring` from point j's pixel
// (row-major).
template <class F>
void for_each_ring_pixel(const PixelMap& map, std::size_t j, int ring, F&& f) {
  const int W = int(map.width), H = int(map.height);
  const int u = int(map.pixel[j] % map.width), v = int(map.pixel[j] / map.width);
  for (int dv = -ring; dv <= ring; ++dv) {
    const int vv = v + dv;
    if (vv < 0 || vv >= H) continue;
    const int step = (dv == -ring || dv == ring) ? 1 : 2 * ring;  // whole edge rows, else ends
    for (int du = -ring; du <= ring; du += step) {
      const int uu = u + du;
      if (uu < 0 || uu >= W) continue;
      const std::int32_t s = map.slot[std::size_t(vv) * map.width + std::size_t(uu)];
      if (s >= 0) f(std::size_t(s));
    }
  }
}

// Calls f(s, ring) for every in-play pixel s of point j's window but its own, ring by ring
// (Chebyshev distance 1, 2, ..., row-major within a ring), so lists start with the pixels next
// to the point.
template <class F>
void for_each_window_pixel(const PixelMap& map, std::size_t j, int h, F&& f) {
  for (int ring = 1; ring <= h; ++ring) for_each_ring_pixel(map, j, ring, [&](std::size_t s) { f(s, ring); });
}

// Each point's distance from the viewpoint, for the continuity test.
struct Ranges {
  std::vector<float> r;
  Ranges(std::span<const Eigen::Vector3f> points, const Eigen::Vector3f& viewpoint)
      : r(points.size()) {
    for (std::size_t j = 0; j < points.size(); ++j) r[j] = (points[j] - viewpoint).norm();
  }
};

// Point j, then the continuous in-play pixels of its window ring by ring, into idx (and their
// squared distances into d2 unless null); returns how many.
std::size_t window_list(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                        const OrganisedConfig& cfg, const Ranges& range, std::size_t j,
                        std::uint32_t* idx, float* d2) {
  const float rj = range.r[j];
  std::size_t c = 0;
  idx[c] = std::uint32_t(j);
  if (d2) d2[c] = 0.0f;
  ++c;
  for_each_window_pixel(map, j, int(cfg.half_window), [&](std::size_t s, int ring) {
    // Symmetric continuity: the allowance uses the mean of the two ranges.
    const float rs = range.r[s];
    if (std::abs(rs - rj) > cfg.depth_change * float(ring) * 0.5f * (rs + rj)) return;
    idx[c] = std::uint32_t(s);
    if (d2) d2[c] = (points[s] - points[j]).squaredNorm();
    ++c;
  });
  return c;
}

// Marks the points whose whole window is surely in play and continuous without listing it:
// every window pixel in the frame and in play, and the window's range spread about the centre,
// max(r_max - r_j, r_j - r_min), within the continuity allowance of a one-pixel step at r_min
// (the least allowance any window pixel gets; 0.999 of it against rounding). A sliding max and
// min over a dense image of ranges (+inf where no point is in play, so the max flags a gap)
// costs a few compares per pixel where a list costs (2h + 1)^2 pixel tests (normals stage
// 6.9 -> 5.3 ms on mOSD_learn0, with the rows skipped below). The points it leaves unmarked are listed as before.
std::vector<char> surely_full(const PixelMap& map, const Ranges& range, std::size_t h, float depth_change) {
  const std::size_t W = map.width, H = map.height;
  constexpr float inf = std::numeric_limits<float>::infinity();
  std::vector<char> full(map.pixel.size(), 0);
  if (W < 2 * h + 1 || H < 2 * h + 1) return full;
  std::vector<float> img(W * H, inf), lo(W * H, inf), hi(W * H, inf);
  for (std::size_t j = 0; j < map.pixel.size(); ++j) img[map.pixel[j]] = range.r[j];
  // Across the rows, then down the columns, over the pixels whose window lies in the frame.
  tbb::parallel_for(std::size_t(0), H, [&](std::size_t v) {
    const float* row = &img[v * W];
    for (std::size_t u = h; u + h < W; ++u) {
      float a = row[u - h], b = a;
      for (std::size_t e = u - h + 1; e <= u + h; ++e) a = std::min(a, row[e]), b = std::max(b, row[e]);
      lo[v * W + u] = a, hi[v * W + u] = b;
    }
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, map.pixel.size(), 4096), [&](const auto& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const std::size_t u = map.pixel[j] % W, v = map.pixel[j] / W;
      if (u < h || u + h >= W || v < h || v + h >= H) continue;
      float a = inf, b = 0.0f;
      for (std::size_t e = v - h; e <= v + h; ++e) a = std::min(a, lo[e * W + u]), b = std::max(b, hi[e * W + u]);
      const float rj = range.r[j];
      full[j] = b < inf && std::max(b - rj, rj - a) <= 0.999f * depth_change * a;
    }
  });
  return full;
}

void check_window(std::uint32_t h) {
  if (h < 1 || h > 7)
    throw Error("preprocess.organised.half_window must be in [1, 7], got " + std::to_string(h));
}

// The ten moments of a set of points (relative to an origin, for precision), summed so that
// points can be added and taken away again: a window's covariance from running sums.
struct Moments {
  std::array<double, 10> s{};  // n, x, y, z, xx, xy, xz, yy, yz, zz
  void add(const Eigen::Vector3d& p, double sign) {
    const double v[10] = {1.0, p.x(), p.y(), p.z(), p.x() * p.x(), p.x() * p.y(),
                          p.x() * p.z(), p.y() * p.y(), p.y() * p.z(), p.z() * p.z()};
    for (int i = 0; i < 10; ++i) s[i] += sign * v[i];
  }
  void add(const Moments& m, double sign) {
    for (int i = 0; i < 10; ++i) s[i] += sign * m.s[i];
  }
  // Covariance (eq. 4.4, divided by N).
  Eigen::Matrix3d covariance() const {
    const double n = s[0];
    const Eigen::Vector3d mean(s[1] / n, s[2] / n, s[3] / n);
    Eigen::Matrix3d c;
    c << s[4] / n, s[5] / n, s[6] / n, s[5] / n, s[7] / n, s[8] / n, s[6] / n, s[8] / n, s[9] / n;
    return c - mean * mean.transpose();
  }
};

// Separable running sums over the rows [v0, v1) of the frame: column sums over the window's
// rows roll down, and a sum over the window's columns slides along each row, so a pixel costs
// the same whatever the window. Calls at(j, moments) for every point j whose window
// it holds whole (full[j]: every window pixel in play and continuous).
template <class At>
void window_moments(const Cloud& cloud, const PixelMap& map, const std::vector<char>& full,
                    std::size_t h, const Eigen::Vector3d& origin, std::size_t v0, std::size_t v1,
                    At&& at) {
  const std::size_t W = map.width, H = map.height;
  // The rows holding a point to compute: the others only roll the column sums on (the sums of
  // a row that is computed do not depend on which rows were), and a block without one is
  // skipped (a frame's table rows, once the plane stage took the table).
  std::vector<char> wanted(v1 - v0, 0);
  for (std::size_t v = v0; v < v1; ++v)
    for (std::size_t u = h; u + h < W && !wanted[v - v0]; ++u)
      if (const std::int32_t j = map.slot[v * W + u]; j >= 0 && full[std::size_t(j)]) wanted[v - v0] = 1;
  if (std::find(wanted.begin(), wanted.end(), 1) == wanted.end()) return;
  std::vector<Moments> col(W);
  const auto add_row = [&](std::size_t v, double sign) {
    if (v >= H) return;  // also the rows above the frame (wrapped below zero)
    for (std::size_t u = 0; u < W; ++u)
      if (const std::int32_t j = map.slot[v * W + u]; j >= 0)
        col[u].add(cloud.points[std::size_t(j)].cast<double>() - origin, sign);
  };
  for (std::size_t v = v0 - h; v != v0 + h; ++v) add_row(v, 1.0);
  for (std::size_t v = v0; v < v1; ++v) {
    add_row(v + h, 1.0);
    if (!wanted[v - v0]) {
      add_row(v - h, -1.0);
      continue;
    }
    Moments run;
    for (std::size_t u = 0; u < std::min(W, 2 * h + 1); ++u) run.add(col[u], 1.0);
    for (std::size_t u = h; u + h < W; ++u) {
      if (u > h) run.add(col[u + h], 1.0), run.add(col[u - h - 1], -1.0);
      const std::int32_t j = map.slot[v * W + u];
      if (j >= 0 && full[std::size_t(j)]) at(std::size_t(j), run);
    }
    add_row(v - h, -1.0);
  }
}
}  // namespace

PixelMap pixel_map(std::uint32_t width, std::uint32_t height, std::vector<std::uint32_t> pixels) {
  PixelMap m;
  m.width = width, m.height = height;
  m.slot.assign(std::size_t(width) * height, -1);
  for (std::size_t j = 0; j < pixels.size(); ++j) {
    if (pixels[j] >= m.slot.size())
      throw Error("pixel_map: pixel " + std::to_string(pixels[j]) + " outside the frame");
    m.slot[pixels[j]] = static_cast<std::int32_t>(j);
  }
  m.pixel = std::move(pixels);
  return m;
}

Neighbours window_neighbours(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                             const OrganisedConfig& cfg, const Eigen::Vector3f& viewpoint) {
  check_window(cfg.half_window);
  const Ranges range(points, viewpoint);
  Neighbours nb;
  nb.k = std::size_t(2 * cfg.half_window + 1) * (2 * cfg.half_window + 1), nb.window = true;
  nb.indices.resize(points.size() * nb.k), nb.sq_dists.resize(points.size() * nb.k);
  nb.count.resize(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024), [&](const auto& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j)
      nb.count[j] = std::uint32_t(window_list(points, map, cfg, range, j, &nb.indices[j * nb.k],
                                              &nb.sq_dists[j * nb.k]));
  });
  return nb;
}

std::vector<float> window_mean_distances(std::span<const Eigen::Vector3f> points,
                                         const PixelMap& map, std::uint32_t half_window,
                                         std::uint32_t k) {
  check_window(half_window);
  const int widest = int(kGrowth * half_window);
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
      for (int ring = 1; ring <= widest && (ring <= int(half_window) || n < k); ++ring)
        for_each_ring_pixel(map, j, ring, [&](std::size_t s) { offer((points[s] - points[j]).squaredNorm()); });
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

void window_normals(Cloud& cloud, const PixelMap& map, const OrganisedConfig& cfg) {
  check_window(cfg.normal_half_window);
  if (map.pixel.size() != cloud.size())
    throw Error("normals: the pixel map does not fit this cloud");
  cloud.normals.resize(cloud.size());
  cloud.curvature.resize(cloud.size());
  if (cloud.empty()) return;
  const auto store = [&](std::size_t j, const PointNormal& pn) {
    cloud.normals[j] = pn.normal;
    cloud.curvature[j] = pn.curvature;
  };
  // Each point's continuous window pixels; a point whose window is cut (by the frame's edge, a
  // gap or a depth step) sums them, the others are marked for the running sums.
  OrganisedConfig own = cfg;
  own.half_window = cfg.normal_half_window;
  const std::size_t whole = std::size_t(2 * own.half_window + 1) * (2 * own.half_window + 1);
  const Ranges range(cloud.points, cloud.viewpoint);
  std::vector<char> full = surely_full(map, range, own.half_window, own.depth_change);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 1024), [&](const auto& r) {
    std::vector<std::uint32_t> list(whole);
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      if (full[j]) continue;
      const std::size_t n = window_list(cloud.points, map, own, range, j, list.data(), nullptr);
      if (n == whole)
        full[j] = 1;
      else
        store(j, normal_from(cloud.points, {list.data(), n}, cloud.points[j], cloud.viewpoint));
    }
  });
  // The others from running sums, in fixed blocks of rows (the sums, and so the output, do not
  // depend on the thread count).
  const Eigen::Vector3d origin = cloud.points[cloud.size() / 2].cast<double>();
  constexpr std::size_t kRows = 16;
  tbb::parallel_for(std::size_t{0}, (map.height + kRows - 1) / kRows, [&](std::size_t b) {
    window_moments(cloud, map, full, own.half_window, origin, b * kRows,
                   std::min<std::size_t>(map.height, (b + 1) * kRows),
                   [&](std::size_t j, const Moments& m) {
                     store(j, normal_from_covariance(m.covariance(), cloud.points[j],
                                                     cloud.viewpoint));
                   });
  });
}

std::vector<PointNormal> window_normals_of(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                                           const OrganisedConfig& cfg, const Eigen::Vector3f& viewpoint,
                                           std::span<const std::uint32_t> which) {
  check_window(cfg.normal_half_window);
  if (map.pixel.size() != points.size()) throw Error("normals: the pixel map does not fit this cloud");
  OrganisedConfig own = cfg;
  own.half_window = cfg.normal_half_window;
  const std::size_t whole = std::size_t(2 * own.half_window + 1) * (2 * own.half_window + 1);
  const Ranges range(points, viewpoint);
  std::vector<PointNormal> out(which.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, which.size(), 256), [&](const auto& r) {
    std::vector<std::uint32_t> list(whole);
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::size_t n = window_list(points, map, own, range, which[i], list.data(), nullptr);
      out[i] = normal_from(points, {list.data(), n}, points[which[i]], viewpoint);
    }
  });
  return out;
}

}  // namespace uwgrasp::cloud
