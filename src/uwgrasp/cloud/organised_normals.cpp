// Normals and curvature over pixel windows (organised.hpp): running sums where a window holds
// whole, the listed pixels elsewhere.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <limits>

#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/organised_window.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

using namespace window_detail;

namespace {
// Marks the points whose window's in-play pixels are surely all continuous with it, without
// listing them: the window in the frame, and its range spread about the centre,
// max(r_max - r_j, r_j - r_min) over the pixels in play, within the continuity allowance of a
// one-pixel step at r_min (the least allowance any window pixel gets; 0.999 of it against
// rounding). Pixels out of play (holes, the removed plane) are left out of the sums as they are
// out of a list, so a window with holes but no depth step takes the running sums too. A sliding
// max and min over a dense image of ranges costs a few compares per pixel where a list costs
// (2h + 1)^2 pixel tests (normals stage 6.9 -> 5.3 ms on mOSD_learn0, with the rows skipped
// below). The points it leaves unmarked are listed as before.
// Into scratch.full (scratch's image, lo, hi, first and last its buffers).
void surely_full(const PixelMap& map, std::span<const float> range, std::size_t h,
                 float depth_change, WindowScratch& scratch) {
  const std::size_t W = map.width, H = map.height;
  constexpr float inf = std::numeric_limits<float>::infinity();
  std::vector<char>& full = scratch.full;
  full.assign(map.pixel.size(), 0);
  if (W < 2 * h + 1 || H < 2 * h + 1) return;
  // lo and hi are read only where the row pass wrote them: left unset (two fewer 1.2 MB fills).
  std::vector<float>& img = scratch.image;
  img.assign(W * H, inf);
  scratch.lo.resize(W * H), scratch.hi.resize(W * H);
  float* const lo = scratch.lo.data();
  float* const hi = scratch.hi.data();
  tbb::parallel_for(std::size_t(0), map.pixel.size(),
                    [&](std::size_t j) { img[map.pixel[j]] = range[j]; });
  // Across the rows, then down the columns, over the pixels whose window lies in the frame and
  // whose column a point within h rows has (a frame's objects, once the plane stage took the
  // table, fill a fraction of it: the whole rows took a fifth of the stage on mOSD_learn0).
  // A pixel out of play is +inf to the min and -inf to the max.
  std::vector<std::size_t>& first = scratch.first;  // each row's in-play columns
  std::vector<std::size_t>& last = scratch.last;
  first.assign(H, W), last.assign(H, 0);
  for (const std::uint32_t p : map.pixel) {
    first[p / W] = std::min<std::size_t>(first[p / W], p % W);
    last[p / W] = std::max<std::size_t>(last[p / W], p % W);
  }
  tbb::parallel_for(std::size_t(0), H, [&](std::size_t v) {
    const float* row = &img[v * W];
    std::size_t from = W, to = 0;
    for (std::size_t e = v < h ? 0 : v - h; e <= std::min(H - 1, v + h); ++e)
      from = std::min(from, first[e]), to = std::max(to, last[e]);
    for (std::size_t u = std::max(h, from); u + h < W && u <= to; ++u) {
      float a = inf, b = -inf;
      for (std::size_t e = u - h; e <= u + h; ++e)
        a = std::min(a, row[e]), b = std::max(b, row[e] == inf ? -inf : row[e]);
      lo[v * W + u] = a, hi[v * W + u] = b;
    }
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, map.pixel.size(), 4096), [&](const auto& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const std::size_t u = map.pixel[j] % W, v = map.pixel[j] / W;
      if (u < h || u + h >= W || v < h || v + h >= H) continue;
      float a = inf, b = -inf;  // the centre is in play: both end finite
      for (std::size_t e = v - h; e <= v + h; ++e)
        a = std::min(a, lo[e * W + u]), b = std::max(b, hi[e * W + u]);
      const float rj = range[j];
      full[j] = std::max(b - rj, rj - a) <= 0.999f * depth_change * a;
    }
  });
}

// The ten moments of a set of points (relative to an origin, for precision): n, x, y, z, xx,
// xy, xz, yy, yz, zz, summed so that points can be added and taken away again: a window's
// covariance from running sums.
using Moments = std::array<double, 10>;
void add(Moments& m, const Eigen::Vector3d& p, double sign) {
  const double v[10] = {1.0,           p.x(),         p.y(),         p.z(),         p.x() * p.x(),
                        p.x() * p.y(), p.x() * p.z(), p.y() * p.y(), p.y() * p.z(), p.z() * p.z()};
  for (int i = 0; i < 10; ++i) m[i] += sign * v[i];
}
void add(Moments& m, const Moments& o, double sign) {
  for (int i = 0; i < 10; ++i) m[i] += sign * o[i];
}
// Covariance (eq. 4.4, divided by N).
Eigen::Matrix3d covariance(const Moments& s) {
  const double n = s[0];
  const Eigen::Vector3d mean(s[1] / n, s[2] / n, s[3] / n);
  Eigen::Matrix3d c;
  c << s[4] / n, s[5] / n, s[6] / n, s[5] / n, s[7] / n, s[8] / n, s[6] / n, s[8] / n, s[9] / n;
  return c - mean * mean.transpose();
}

// Separable running sums over the rows [v0, v1) of the frame: column sums over the window's
// rows roll down, and a sum over the window's columns slides along each row, so a pixel costs
// the same whatever the window. Calls at(j, moments) for every point j whose window
// it takes (full[j]: the window in the frame and its in-play pixels continuous). `wanted` (a
// flag per row of the block) and `col` (per column) are the block's scratch (cleared here: the
// result does not depend on what they held).
template <class At>
void window_moments(const Cloud& cloud, const PixelMap& map, const std::vector<char>& full,
                    std::size_t h, const Eigen::Vector3d& origin, std::size_t v0, std::size_t v1,
                    std::span<char> wanted, std::span<Moments> col, At&& at) {
  const std::size_t W = map.width, H = map.height;
  // The rows holding a point to compute: the others only roll the column sums on (the sums of
  // a row that is computed do not depend on which rows were), and a block without one is
  // skipped (a frame's table rows, once the plane stage took the table).
  std::fill(wanted.begin(), wanted.end(), 0);
  for (std::size_t v = v0; v < v1; ++v)
    for (std::size_t u = h; u + h < W && !wanted[v - v0]; ++u)
      if (const std::int32_t j = map.slot[v * W + u]; j >= 0 && full[std::size_t(j)]) wanted[v - v0] = 1;
  if (std::find(wanted.begin(), wanted.end(), 1) == wanted.end()) return;
  std::fill(col.begin(), col.end(), Moments{});
  const auto add_row = [&](std::size_t v, double sign) {
    if (v >= H) return;  // also the rows above the frame (wrapped below zero)
    for (std::size_t u = 0; u < W; ++u)
      if (const std::int32_t j = map.slot[v * W + u]; j >= 0)
        add(col[u], cloud.points[std::size_t(j)].cast<double>() - origin, sign);
  };
  for (std::size_t v = v0 - h; v != v0 + h; ++v) add_row(v, 1.0);
  for (std::size_t v = v0; v < v1; ++v) {
    add_row(v + h, 1.0);
    if (!wanted[v - v0]) {
      add_row(v - h, -1.0);
      continue;
    }
    Moments run{};
    for (std::size_t u = 0; u < std::min(W, 2 * h + 1); ++u) add(run, col[u], 1.0);
    for (std::size_t u = h; u + h < W; ++u) {
      if (u > h) add(run, col[u + h], 1.0), add(run, col[u - h - 1], -1.0);
      const std::int32_t j = map.slot[v * W + u];
      if (j >= 0 && full[std::size_t(j)]) at(std::size_t(j), run);
    }
    add_row(v - h, -1.0);
  }
}
}  // namespace

void window_normals(Cloud& cloud, const PixelMap& map, const OrganisedConfig& cfg) {
  WindowScratch scratch;
  window_normals(cloud, map, cfg, scratch);
}

void window_normals(Cloud& cloud, const PixelMap& map, const OrganisedConfig& cfg,
                    WindowScratch& scratch) {
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
  const std::uint32_t h = cfg.normal_half_window;
  const std::size_t whole = std::size_t(2 * h + 1) * (2 * h + 1);
  const std::span<const float> range = ranges(cloud.points, cloud.viewpoint, scratch.range);
  const WindowTable table(map.width, h);
  surely_full(map, range, h, cfg.depth_change, scratch);
  std::vector<char>& full = scratch.full;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 1024), [&](const auto& r) {
    std::array<std::uint32_t, kMaxWindow> list;  // whole <= kMaxWindow (check_window)
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      if (full[j]) continue;
      const std::size_t n = window_list(cloud.points, map, table, cfg.depth_change, range, j, list.data(), nullptr);
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
  const std::size_t blocks = (map.height + kRows - 1) / kRows;
  // Each block's own scratch rows in the workspace (a frame's blocks ask the allocator once).
  const std::size_t W = map.width;
  scratch.columns.resize(blocks * W), scratch.wanted.resize(blocks * kRows);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks), [&](const auto& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      const std::size_t v0 = b * kRows, v1 = std::min<std::size_t>(map.height, v0 + kRows);
      const std::span<char> wanted = std::span(scratch.wanted).subspan(b * kRows, v1 - v0);
      const std::span<Moments> col = std::span(scratch.columns).subspan(b * W, W);
      window_moments(
          cloud, map, full, h, origin, v0, v1, wanted, col, [&](std::size_t j, const Moments& m) {
            // Fewer than three pixels in play: no normal, as from a list.
            store(j, m[0] < 3.0
                         ? PointNormal{}
                         : normal_from_covariance(covariance(m), cloud.points[j], cloud.viewpoint));
          });
    }
  });
}

void window_normals_of(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                       const OrganisedConfig& cfg, const Eigen::Vector3f& viewpoint,
                       std::span<const std::uint32_t> which, std::vector<PointNormal>& out,
                       WindowScratch& scratch) {
  check_window(cfg.normal_half_window);
  if (map.pixel.size() != points.size())
    throw Error("normals: the pixel map does not fit this cloud");
  const std::span<const float> range = ranges(points, viewpoint, scratch.range);
  const WindowTable table(map.width, cfg.normal_half_window);
  out.resize(which.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, which.size(), 256), [&](const auto& r) {
    std::array<std::uint32_t, kMaxWindow> list;  // a window's pixels (check_window above)
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::size_t n = window_list(points, map, table, cfg.depth_change, range, which[i], list.data(), nullptr);
      out[i] = normal_from(points, {list.data(), n}, points[which[i]], viewpoint);
    }
  });
}

}  // namespace uwgrasp::cloud
