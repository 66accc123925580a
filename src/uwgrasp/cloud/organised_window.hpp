#pragma once
// The pixel windows of an organised frame that organised.cpp and organised_normals.cpp share
// (organised.hpp): iterating a point's window ring by ring, the ranges the continuity test
// compares, and a point's continuous window list. Internal to cloud/.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud::window_detail {

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

// The most pixels a window holds (check_window: h <= 7), for lists on the stack.
constexpr std::size_t kMaxWindow = 15 * 15;

inline void check_window(std::uint32_t h) {
  if (h < 1 || h > 7)
    throw Error("preprocess.organised.half_window must be in [1, 7], got " + std::to_string(h));
}

// The pixels of a window of half width h around its centre, as offsets in the frame's row-major
// index, in the order for_each_window_pixel visits them (ring by ring, row-major within a ring),
// with their rings: a point whose whole window lies in the frame walks the table without a
// bounds test per pixel (window lists 2.4 -> 1.2 ms on mOSD_learn0, outlier statistic 3.8 -> 3.4
// ms). Fixed arrays: three tables a frame, none asking the allocator.
struct WindowTable {
  int h = 0;
  std::size_t size = 0;
  std::array<std::ptrdiff_t, kMaxWindow> offset{};
  std::array<int, kMaxWindow> ring{};
  std::array<std::int8_t, kMaxWindow> col{}, row{};  // each pixel's offsets du and dv
  WindowTable(std::uint32_t width, std::uint32_t half) : h(int(half)) {
    check_window(half);
    for (int r = 1; r <= h; ++r)
      for (int dv = -r; dv <= r; ++dv) {
        const int step = (dv == -r || dv == r) ? 1 : 2 * r;
        for (int du = -r; du <= r; du += step) {
          offset[size] = std::ptrdiff_t(dv) * std::ptrdiff_t(width) + du;
          col[size] = std::int8_t(du), row[size] = std::int8_t(dv);
          ring[size++] = r;
        }
      }
  }
};

// for_each_window_pixel over the table's window: the same pixels in the same order.
template <class F>
void for_each_window_pixel(const PixelMap& map, const WindowTable& t, std::size_t j, F&& f) {
  const std::size_t p = map.pixel[j], u = p % map.width, v = p / map.width, h = std::size_t(t.h);
  if (u < h || u + h >= map.width || v < h || v + h >= map.height) {
    for_each_window_pixel(map, j, t.h, f);
    return;
  }
  const std::int32_t* centre = map.slot.data() + p;
  for (std::size_t i = 0; i < t.size; ++i)
    if (const std::int32_t s = centre[t.offset[i]]; s >= 0) f(std::size_t(s), t.ring[i]);
}

// Each point's distance from the viewpoint, for the continuity test, into `r` (in parallel: a
// frame's 250k square roots, three times a frame).
inline std::span<const float> ranges(std::span<const Eigen::Vector3f> points,
                                     const Eigen::Vector3f& viewpoint, std::vector<float>& r) {
  r.resize(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 8192), [&](const auto& b) {
    for (std::size_t j = b.begin(); j != b.end(); ++j) r[j] = (points[j] - viewpoint).norm();
  });
  return r;
}

// Point j, then the continuous in-play pixels of its window ring by ring, into idx (and their
// squared distances into d2 unless null); returns how many.
inline std::size_t window_list(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                               const WindowTable& table, float depth_change,
                               std::span<const float> range, std::size_t j, std::uint32_t* idx,
                               float* d2) {
  const float rj = range[j];
  std::size_t c = 0;
  idx[c] = std::uint32_t(j);
  if (d2) d2[c] = 0.0f;
  ++c;
  for_each_window_pixel(map, table, j, [&](std::size_t s, int ring) {
    // Symmetric continuity: the allowance uses the mean of the two ranges.
    const float rs = range[s];
    if (std::abs(rs - rj) > depth_change * float(ring) * 0.5f * (rs + rj)) return;
    idx[c] = std::uint32_t(s);
    if (d2) d2[c] = (points[s] - points[j]).squaredNorm();
    ++c;
  });
  return c;
}

}  // namespace uwgrasp::cloud::window_detail
