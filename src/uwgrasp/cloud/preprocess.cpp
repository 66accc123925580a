// The preprocessing chain (preprocess.hpp): what both paths share, and the choice between them.
#include "uwgrasp/cloud/preprocess.hpp"

#include <tbb/parallel_for.h>

#include <cstdio>
#include <string>
#include <utility>

#include "uwgrasp/cloud/indices.hpp"
#include "uwgrasp/cloud/plane_stage.hpp"
#include "uwgrasp/cloud/preprocess_paths.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

namespace preprocess_detail {
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

void keep_masked(Cloud& cur, Workspace& ws, std::vector<std::int32_t>& map) {
  indices_where(
      cur.size(), [&](std::size_t i) { return ws.mask[i] != 0; }, ws.kept);
  if (ws.kept.size() == cur.size()) return;  // nothing dropped (cur is already unorganised)
  select(cur, ws.kept, ws.next);
  remap_filtered(map, ws.kept, cur.size(), ws.position);
  std::swap(cur, ws.next);
}

// Widened to the measured noise.
void remove_plane(Cloud& cur, const PreprocessConfig& cfg, std::uint64_t seed, Preprocessed& out,
                  Workspace& ws, const PixelMap* map) {
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

void require_points(const Cloud& c, const char* stage) {
  if (c.empty()) throw Error(std::string("preprocess: no points left after the ") + stage +
                             " stage");
}

}  // namespace preprocess_detail

namespace {
using namespace preprocess_detail;

bool takes_organised_path(const Cloud& in, const PreprocessConfig& cfg) {
  return in.organised() && cfg.organised.enabled && !cfg.voxel.enabled &&
         cfg.normals.radius <= 0.0f;
}

// Everything a previous frame left in `out` that a stage may not overwrite.
void reset(Preprocessed& out, std::size_t input_size) {
  out.plane.found = false, out.plane.coefficients.setZero(), out.plane.iterations = 0;
  out.plane.inliers.clear();
  out.plane_is_face = false, out.noise = {}, out.counts = {}, out.organised = false;
  out.noise_footprints = 0.0, out.normal_half_window = 0, out.moved_depth_error = 0.0;
  out.neighbours.k = 0, out.neighbours.window = false;
  out.neighbours.indices.clear(), out.neighbours.sq_dists.clear(), out.neighbours.count.clear();
  out.counts.input = input_size;
  out.output_of_input.resize(input_size);
  for (std::size_t i = 0; i < input_size; ++i)
    out.output_of_input[i] = static_cast<std::int32_t>(i);
  out.plane_of_input.assign(input_size, 0);
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

std::string normals_summary(const Preprocessed& p) {
  if (!p.organised) return {};
  const std::string side = std::to_string(2 * p.normal_half_window + 1);
  char noise[32];
  std::snprintf(noise, sizeof noise, "%.2f", p.noise_footprints);
  std::string line =
      side + " x " + side + " pixel windows (depth noise " + noise + " pixel footprints)";
  if (p.moved_depth_error > 0.0) {
    char left[96];
    std::snprintf(left, sizeof left,
                  "; points moved onto their windows' range fits, %.2f mm left at 1 m",
                  1e3 * p.moved_depth_error);
    line += left;
  }
  return line;
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
