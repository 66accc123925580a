// The preprocessing chain on an organised frame (preprocess.hpp): the stages on pixel windows.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <functional>

#include "uwgrasp/cloud/indices.hpp"
#include "uwgrasp/cloud/preprocess_paths.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud::preprocess_detail {

namespace {
// The pixel of every point still in play, from the input map (input index = pixel index), into
// m: the map's slots are the input map itself, copied rather than filled and scattered again.
void pixels_in_play(const Cloud& in, const std::vector<std::int32_t>& output_of_input,
                    std::size_t size, PixelMap& m) {
  m.width = in.width, m.height = in.height;
  m.slot = output_of_input;  // into the slots' buffer: no allocation once it holds a frame
  m.pixel.resize(size);
  tbb::parallel_for(std::size_t(0), output_of_input.size(), [&](std::size_t i) {
    if (output_of_input[i] >= 0) m.pixel[std::size_t(output_of_input[i])] = std::uint32_t(i);
  });
}

// Invalid values (4.1.1) and the range crop in one parallel pass that keeps each point's pixel,
// into out.cloud.
void valid_points(const Cloud& in, const RangeConfig& range, Preprocessed& out, Workspace& ws) {
  const float lo2 = range.min * range.min, hi2 = range.max * range.max;
  const auto valid = [&](std::size_t i) {
    if (!is_finite(in.points[i])) return false;
    const float r2 = (in.points[i] - in.viewpoint).squaredNorm();
    return !range.enabled || (r2 >= lo2 && r2 <= hi2);
  };
  indices_where(in.size(), valid, ws.kept);
  const std::vector<std::uint32_t>& kept = ws.kept;
  out.counts.finite =
      range.enabled ? tbb::parallel_reduce(
                          tbb::blocked_range<std::size_t>(0, in.size(), 1 << 14), std::size_t(0),
                          [&](const auto& r, std::size_t c) {
                            for (std::size_t i = r.begin(); i != r.end(); ++i)
                              c += is_finite(in.points[i]) ? 1 : 0;
                            return c;
                          },
                          std::plus<>())
                    : kept.size();
  if (out.counts.finite == 0)
    throw Error("input cloud has no finite point (all x/y/z are NaN or Inf)");
  out.counts.in_range = out.counts.voxels = kept.size();
  std::fill(out.output_of_input.begin(), out.output_of_input.end(), -1);
  tbb::parallel_for(std::size_t(0), kept.size(),
                    [&](std::size_t j) { out.output_of_input[kept[j]] = std::int32_t(j); });
  select(in, kept, out.cloud);
}

}  // namespace

// The chain on an organised frame (preprocess.hpp): the same stages, neighbourhoods from pixel
// windows. The running cloud is out.cloud itself; each filter writes ws.next and swaps it in.
void preprocess_organised(const Cloud& in, const PreprocessConfig& cfg, std::uint64_t seed,
                          StageTimer& timer, Preprocessed& out, Workspace& ws) {
  out.organised = true;
  Cloud& cur = out.cloud;
  timer.start("finite");
  valid_points(in, cfg.range, out, ws);
  require_points(cur, "range");
  if (cfg.water.enabled) {
    timer.start("color");
    restore_colors(cur, cfg.water);
  }
  if (cfg.plane.enabled) {
    timer.start("plane");
    pixels_in_play(in, out.output_of_input, cur.size(), ws.map);
    remove_plane(cur, cfg, seed, out, ws, &ws.map);
  }
  timer.start("outliers");
  pixels_in_play(in, out.output_of_input, cur.size(), ws.map);
  if (cfg.outliers.enabled) {
    window_mean_distances(cur.points, ws.map, cfg.organised.half_window, cfg.outliers.k, ws.mean);
    outlier_mask(cfg.outliers, ws.mean, ws.mask);
    const std::size_t before = cur.size();
    keep_masked(cur, ws, out.output_of_input);
    if (cur.size() != before) pixels_in_play(in, out.output_of_input, cur.size(), ws.map);
  }
  require_points(cur, "outliers");  // e.g. a frame of isolated pixels
  // The lists of the points kept only (the outlier statistic takes every in-play pixel).
  window_neighbours(cur.points, ws.map, cfg.organised, cur.viewpoint, out.neighbours, ws.window);
  out.counts.after_outliers = cur.size();
  timer.start("normals");
  // A noisier sensor than the default's gets a wider normal window (organised.hpp).
  OrganisedConfig normal_cfg = cfg.organised;
  if (cfg.organised.max_normal_slope > 0.0f)
    out.noise_footprints =
        noise_per_pixel(cur.points, ws.map, cur.viewpoint, cfg.organised.depth_change, ws.window);
  out.normal_half_window = normal_cfg.normal_half_window =
      normal_window(out.noise_footprints, cfg.organised);
  // A noisy frame's points onto quadratics fitted to their windows' ranges, and their lists
  // again from the moved points (organised.hpp): the fit has averaged the noise a point
  // carries. The move reads only the ranges, so the normals come once, from the moved points.
  if (cfg.organised.move_onto_quadrics &&
      normal_cfg.normal_half_window > cfg.organised.normal_half_window) {
    out.moved_depth_error = move_onto_quadrics(cur, ws.map, normal_cfg, ws.window).left;
    window_neighbours(cur.points, ws.map, cfg.organised, cur.viewpoint, out.neighbours, ws.window);
  }
  window_normals(cur, ws.map, normal_cfg, ws.window);
  timer.stop();
  out.counts.output = cur.size();
}

}  // namespace uwgrasp::cloud::preprocess_detail
