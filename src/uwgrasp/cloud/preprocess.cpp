#include "uwgrasp/cloud/preprocess.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>

#include "uwgrasp/cloud/indices.hpp"
#include "uwgrasp/cloud/plane_stage.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

namespace {
// After a filter that kept `kept` (indices into the previous cloud), re-point the map.
void remap_filtered(std::vector<std::int32_t>& map, const std::vector<std::uint32_t>& kept,
                    std::size_t previous_size, std::vector<std::int32_t>& pos) {
  if (kept.size() == previous_size) return;  // kept is ascending: nothing was dropped
  // In parallel (each entry is written once): a frame's 300k pixels, three times per frame.
  pos.assign(previous_size, -1);
  tbb::parallel_for(std::size_t(0), kept.size(), [&](std::size_t j) { pos[kept[j]] = static_cast<std::int32_t>(j); });
  tbb::parallel_for(std::size_t(0), map.size(), [&](std::size_t i) {
    if (map[i] >= 0) map[i] = pos[static_cast<std::size_t>(map[i])];
  });
}

void remap_filtered(std::vector<std::int32_t>& map, const std::vector<std::uint32_t>& kept,
                    std::size_t previous_size) {
  std::vector<std::int32_t> pos;
  remap_filtered(map, kept, previous_size, pos);
}

// Applies a filter's result to the running cloud and the input map.
void apply(Filtered&& f, Cloud& cur, std::vector<std::int32_t>& map) {
  remap_filtered(map, f.indices, cur.size());
  cur = std::move(f.cloud);
}

// Keeps the points of `cur` whose ws.mask entry is set (through ws.next, swapped in) and
// re-points the map; the organised path's filters, without a buffer of their own.
void keep_masked(Cloud& cur, Workspace& ws, std::vector<std::int32_t>& map) {
  indices_where(
      cur.size(), [&](std::size_t i) { return ws.mask[i] != 0; }, ws.kept);
  if (ws.kept.size() == cur.size()) return;  // nothing dropped (cur is already unorganised)
  select(cur, ws.kept, ws.next);
  remap_filtered(map, ws.kept, cur.size(), ws.position);
  std::swap(cur, ws.next);
}

// The plane (4.1.4), widened to the measured noise; `map` (organised frames) lets the normals
// keep an object's foot.
void remove_plane(Cloud& cur, const PreprocessConfig& cfg, std::uint64_t seed, Preprocessed& out,
                  Workspace& ws, const PixelMap* map = nullptr) {
  fit_plane(cur, cfg.plane, seed, out.plane);
  if (out.plane.found && cfg.plane.support_only &&
      !supports_the_rest(cur, cfg.plane, out.plane, ws.plane)) {
    out.plane.found = false;  // a face of the object (object-only clouds): nothing to remove
    out.plane.inliers.clear();
    out.plane_is_face = true;
  }
  if (out.plane.found && cfg.plane.noise_sigmas > 0.0f)
    widen_to_noise(cur, cfg.plane, out, ws.plane);
  if (out.plane.found && map && cfg.plane.normal_angle > 0.0f)
    keep_turned_points(cur, *map, cfg, out.plane, ws.plane, ws.window);
  if (!out.plane.found && cfg.plane.required)
    throw Error("preprocess: no plane found (preprocess.plane.distance = " +
                std::to_string(cfg.plane.distance) + " m)");
  if (!out.plane.found) return;
  ws.mask.assign(cur.size(), 1);
  tbb::parallel_for(std::size_t(0), out.plane.inliers.size(),
                    [&](std::size_t k) { ws.mask[out.plane.inliers[k]] = 0; });
  tbb::parallel_for(std::size_t(0), out.output_of_input.size(), [&](std::size_t i) {
    const auto m = out.output_of_input[i];
    if (m >= 0 && !ws.mask[static_cast<std::size_t>(m)]) out.plane_of_input[i] = 1;
  });
  keep_masked(cur, ws, out.output_of_input);
  out.counts.plane = out.plane.inliers.size();
}

void voxelise(Cloud& cur, const VoxelConfig& cfg, std::vector<std::int32_t>& map) {
  VoxelResult v = voxel_grid(cur, cfg);
  for (auto& m : map)
    if (m >= 0) {
      const std::uint32_t to = v.voxel_of[static_cast<std::size_t>(m)];
      m = to == VoxelResult::kDropped ? -1 : static_cast<std::int32_t>(to);
    }
  cur = std::move(v.cloud);
}

void normals_stage(Cloud& cur, const NormalConfig& cfg, std::size_t share_k, Preprocessed& out) {
  if (cfg.radius > 0.0f || cur.empty()) {
    compute_normals(cur, cfg);
    return;
  }
  const KdTree tree(cur.points);
  const std::size_t k = std::min<std::size_t>(std::max<std::size_t>(cfg.k, share_k), cur.size());
  out.neighbours = knn_all(tree, cur.points, k);
  compute_normals(cur, cfg, out.neighbours);
}

// Outlier removal (4.1.3) and the normals (4.2.1) from one k-nearest search: the normals' lists
// are the outlier search's rows without the removed points (restrict_neighbours), so the cloud
// is searched once instead of twice - the search is most of both stages.
void outliers_then_normals(Cloud& cur, const PreprocessConfig& cfg, std::size_t share_k,
                           Preprocessed& out, StageTimer& timer) {
  const std::size_t normal_k = std::max<std::size_t>(cfg.normals.k, share_k);
  const KdTree tree(cur.points);
  const Neighbours all = knn_all(
      tree, cur.points,
      std::min(std::max(normal_k, std::size_t{cfg.outliers.k} + 1), cur.size()));
  Filtered f = remove_outliers(cur, cfg.outliers, all);
  out.counts.after_outliers = f.cloud.size();
  timer.start("normals");
  out.neighbours = restrict_neighbours(tree, all, f.indices, normal_k);
  apply(std::move(f), cur, out.output_of_input);
  compute_normals(cur, cfg.normals, out.neighbours);
}

// The outlier stage (if enabled), then the normals: one shared search when both use k nearest
// neighbours and the outlier stage has more than k points to judge.
void outliers_and_normals(Cloud& cur, const PreprocessConfig& cfg, std::size_t share_k,
                          Preprocessed& out, StageTimer& timer) {
  if (cfg.outliers.enabled && cfg.outliers.k > 0 && cur.size() > cfg.outliers.k &&
      cfg.normals.radius <= 0.0f) {
    timer.start("outliers");  // the shared search is timed here
    outliers_then_normals(cur, cfg, share_k, out, timer);
    return;
  }
  if (cfg.outliers.enabled) {
    timer.start("outliers");
    apply(remove_outliers(cur, cfg.outliers), cur, out.output_of_input);
  }
  out.counts.after_outliers = cur.size();
  timer.start("normals");
  normals_stage(cur, cfg.normals, share_k, out);
}

void require_points(const Cloud& c, const char* stage) {
  if (c.empty()) throw Error(std::string("preprocess: no points left after the ") + stage +
                             " stage");
}

bool takes_organised_path(const Cloud& in, const PreprocessConfig& cfg) {
  return in.organised() && cfg.organised.enabled && !cfg.voxel.enabled &&
         cfg.normals.radius <= 0.0f;
}

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
  out.counts.finite = range.enabled ? tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, in.size(), 1 << 14), std::size_t(0),
      [&](const auto& r, std::size_t c) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) c += is_finite(in.points[i]) ? 1 : 0;
        return c;
      },
      std::plus<>()) : kept.size();
  if (out.counts.finite == 0)
    throw Error("input cloud has no finite point (all x/y/z are NaN or Inf)");
  out.counts.in_range = out.counts.voxels = kept.size();
  std::fill(out.output_of_input.begin(), out.output_of_input.end(), -1);
  tbb::parallel_for(std::size_t(0), kept.size(), [&](std::size_t j) { out.output_of_input[kept[j]] = std::int32_t(j); });
  select(in, kept, out.cloud);
}

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
  window_normals(cur, ws.map, cfg.organised, ws.window);
  timer.stop();
  out.counts.output = cur.size();
}

// Everything a previous frame left in `out` that a stage may not overwrite.
void reset(Preprocessed& out, std::size_t input_size) {
  out.plane.found = false, out.plane.coefficients.setZero(), out.plane.iterations = 0;
  out.plane.inliers.clear();
  out.plane_is_face = false, out.noise = {}, out.counts = {}, out.organised = false;
  out.neighbours.k = 0, out.neighbours.window = false;
  out.neighbours.indices.clear(), out.neighbours.sq_dists.clear(), out.neighbours.count.clear();
  out.counts.input = input_size;
  out.output_of_input.resize(input_size);
  for (std::size_t i = 0; i < input_size; ++i)
    out.output_of_input[i] = static_cast<std::int32_t>(i);
  out.plane_of_input.assign(input_size, 0);
}

// The chain on any other cloud, with k-d tree neighbourhoods.
void preprocess_unorganised(const Cloud& in, const PreprocessConfig& cfg, std::uint64_t seed,
                            StageTimer& timer, std::size_t share_k, Preprocessed& out,
                            Workspace& ws) {
  timer.start("finite");
  Filtered f = remove_invalid(in);
  if (f.cloud.empty()) throw Error("input cloud has no finite point (all x/y/z are NaN or Inf)");
  remap_filtered(out.output_of_input, f.indices, in.size());
  Cloud cur = std::move(f.cloud);
  out.counts.finite = cur.size();
  if (cfg.water.enabled) {
    timer.start("color");
    restore_colors(cur, cfg.water);
  }
  if (cfg.range.enabled) {
    timer.start("range");
    // Usually every point is in range: then the cloud is neither copied nor remapped.
    std::vector<std::uint32_t> kept = in_range(cur, cfg.range);
    if (kept.size() != cur.size())
      apply({select(cur, kept), std::move(kept)}, cur, out.output_of_input);
    require_points(cur, "range");
  }
  out.counts.in_range = cur.size();
  if (cfg.voxel.enabled) {
    timer.start("voxel");
    voxelise(cur, cfg.voxel, out.output_of_input);
    require_points(cur, "voxel");
  }
  out.counts.voxels = cur.size();
  if (cfg.plane.enabled) {
    timer.start("plane");
    remove_plane(cur, cfg, seed, out, ws);
  }
  outliers_and_normals(cur, cfg, share_k, out, timer);
  timer.stop();
  out.counts.output = cur.size();
  out.cloud = std::move(cur);
}
}  // namespace

Preprocessed preprocess(const Cloud& in, const PreprocessConfig& cfg, std::uint64_t seed,
                        StageTimer& timer, std::size_t share_k) {
  Preprocessed out;
  Workspace ws;
  preprocess(in, cfg, seed, timer, out, ws, share_k);
  return out;
}

void preprocess(const Cloud& in, const PreprocessConfig& cfg, std::uint64_t seed, StageTimer& timer,
                Preprocessed& out, Workspace& ws, std::size_t share_k) {
  check_consistent(in, "input cloud");
  if (in.empty()) throw Error("input cloud is empty");
  reset(out, in.size());
  if (takes_organised_path(in, cfg))
    preprocess_organised(in, cfg, seed, timer, out, ws);
  else
    preprocess_unorganised(in, cfg, seed, timer, share_k, out, ws);
}

std::string path_summary(const Cloud& in, const PreprocessConfig& cfg) {
  if (takes_organised_path(in, cfg)) {
    const std::string side = std::to_string(2 * cfg.organised.half_window + 1);
    return "organised (" + std::to_string(in.width) + " x " + std::to_string(in.height) +
           " frame, " + side + " x " + side + " pixel windows)";
  }
  const char* why = !in.organised()             ? "unorganised cloud"
                    : !cfg.organised.enabled    ? "preprocess.organised.enabled is false"
                    : cfg.voxel.enabled         ? "the voxel grid is on"
                                                : "radius normals";
  return std::string("k-d tree (") + why + ")";
}

}  // namespace uwgrasp::cloud
