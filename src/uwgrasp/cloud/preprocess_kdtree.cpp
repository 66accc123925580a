// The preprocessing chain on an unorganised cloud (preprocess.hpp): the stages on k-d tree
// neighbourhoods.
#include <algorithm>
#include <utility>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/cloud/preprocess_paths.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud::preprocess_detail {

namespace {
// Applies a filter's result to the running cloud and the input map.
void apply(Filtered&& f, Cloud& cur, std::vector<std::int32_t>& map) {
  remap_filtered(map, f.indices, cur.size());
  cur = std::move(f.cloud);
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
      tree, cur.points, std::min(std::max(normal_k, std::size_t{cfg.outliers.k} + 1), cur.size()));
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

}  // namespace

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

}  // namespace uwgrasp::cloud::preprocess_detail
