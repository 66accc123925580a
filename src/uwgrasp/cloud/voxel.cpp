#include "uwgrasp/cloud/voxel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <span>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/cloud/radix_sort.hpp"

namespace uwgrasp::cloud {

namespace {
constexpr std::uint64_t kNoKey = std::numeric_limits<std::uint64_t>::max();

std::uint32_t majority(std::vector<std::uint32_t>& labels) {
  std::sort(labels.begin(), labels.end());
  std::uint32_t best = labels.front(), run = 0, best_run = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    run = (i > 0 && labels[i] == labels[i - 1]) ? run + 1 : 1;
    if (run > best_run) best_run = run, best = labels[i];
  }
  return best;
}

// Writes the centroid of the points `members` (every attribute the cloud has) to slot o of `out`,
// whose attribute vectors are already sized.
void centroid_into(const Cloud& in, std::span<const std::uint32_t> members, Cloud& out, std::size_t o) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
  double curv = 0.0, rgb[3] = {0, 0, 0};
  std::vector<std::uint32_t> labels;
  for (const std::uint32_t i : members) {
    p += in.points[i].cast<double>();
    if (in.has_normals() && is_finite(in.normals[i])) n += in.normals[i].cast<double>();
    if (in.has_curvature() && std::isfinite(in.curvature[i])) curv += in.curvature[i];
    if (in.has_colors()) rgb[0] += in.colors[i].r, rgb[1] += in.colors[i].g, rgb[2] += in.colors[i].b;
    if (in.has_labels()) labels.push_back(in.labels[i]);
  }
  const double c = double(members.size());
  out.points[o] = (p / c).cast<float>();
  if (in.has_normals()) {
    const double len = n.norm();
    out.normals[o] = len > 0 ? Eigen::Vector3f((n / len).cast<float>())
                             : Eigen::Vector3f::Constant(std::nanf(""));
  }
  if (in.has_curvature()) out.curvature[o] = static_cast<float>(curv / c);
  if (in.has_colors()) {
    auto avg = [&](int ch) { return static_cast<std::uint8_t>(std::lround(rgb[ch] / c)); };
    out.colors[o] = {avg(0), avg(1), avg(2)};
  }
  if (in.has_labels()) out.labels[o] = majority(labels);
}

// Sizes every attribute the input has to n slots.
void size_like(const Cloud& in, std::size_t n, Cloud& out) {
  out.points.assign(n, Eigen::Vector3f::Zero());
  if (in.has_normals()) out.normals.assign(n, Eigen::Vector3f::Zero());
  if (in.has_curvature()) out.curvature.assign(n, 0.0f);
  if (in.has_colors()) out.colors.assign(n, Rgb8{});
  if (in.has_labels()) out.labels.assign(n, 0u);
}

// Voxel key of every point (kNoKey for non-finite points), as PCL computes it.
std::vector<std::uint64_t> voxel_keys(const Cloud& in, float leaf) {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f hi = -lo;
  for (const auto& p : in.points)
    if (is_finite(p)) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  std::vector<std::uint64_t> keys(in.size(), kNoKey);
  if (lo.x() > hi.x()) return keys;
  const float inv = 1.0f / leaf;
  Eigen::Array3d min_b, div;
  for (int a = 0; a < 3; ++a) {
    min_b[a] = std::floor(lo[a] * inv);
    div[a] = std::floor(hi[a] * inv) - min_b[a] + 1.0;
  }
  if (div.prod() > 9.0e18) {
    throw Error("voxel grid: leaf " + std::to_string(leaf) +
                " m is too small for a cloud this large (voxel indices would overflow)");
  }
  const std::uint64_t dx = static_cast<std::uint64_t>(div[0]);
  const std::uint64_t dxy = dx * static_cast<std::uint64_t>(div[1]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.size(), 1 << 14), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Eigen::Vector3f& p = in.points[i];
      if (!is_finite(p)) continue;
      const auto ix = static_cast<std::uint64_t>(std::floor(p.x() * inv) - min_b[0]);
      const auto iy = static_cast<std::uint64_t>(std::floor(p.y() * inv) - min_b[1]);
      const auto iz = static_cast<std::uint64_t>(std::floor(p.z() * inv) - min_b[2]);
      keys[i] = ix + iy * dx + iz * dxy;
    }
  });
  return keys;
}
}  // namespace

VoxelResult voxel_grid(const Cloud& in, const VoxelConfig& cfg) {
  if (!(cfg.leaf > 0.0f) || !std::isfinite(cfg.leaf))
    throw Error("voxel grid: leaf must be > 0, got " + std::to_string(cfg.leaf));
  const std::vector<std::uint64_t> all_keys = voxel_keys(in, cfg.leaf);
  std::vector<std::uint64_t> keys;
  std::vector<std::uint32_t> idx;
  keys.reserve(in.size()), idx.reserve(in.size());
  std::uint64_t max_key = 0;
  for (std::size_t i = 0; i < in.size(); ++i)
    if (all_keys[i] != kNoKey)
      keys.push_back(all_keys[i]), idx.push_back(std::uint32_t(i)), max_key = std::max(max_key, all_keys[i]);
  radix_sort(keys, idx, std::max(1, int(std::bit_width(max_key))));
  VoxelResult res;
  res.voxel_of.assign(in.size(), VoxelResult::kDropped);
  res.cloud.viewpoint = in.viewpoint;
  // Each run of equal keys is one voxel, already in PCL's order (ascending voxel index); the
  // kept runs' centroids are independent, so they are computed in parallel.
  std::vector<std::uint32_t> start;
  for (std::size_t a = 0, b = 0; a < keys.size(); a = b) {
    while (b < keys.size() && keys[b] == keys[a]) ++b;
    if (b - a >= std::max<std::uint32_t>(1, cfg.min_points)) start.push_back(std::uint32_t(a));
  }
  const auto run_end = [&](std::uint32_t a) {
    std::size_t b = a;
    while (b < keys.size() && keys[b] == keys[a]) ++b;
    return b;
  };
  size_like(in, start.size(), res.cloud);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, start.size(), 256), [&](const auto& r) {
    for (std::size_t o = r.begin(); o != r.end(); ++o) {
      const std::size_t a = start[o], b = run_end(start[o]);
      for (std::size_t j = a; j < b; ++j) res.voxel_of[idx[j]] = std::uint32_t(o);
      centroid_into(in, std::span<const std::uint32_t>(&idx[a], b - a), res.cloud, o);
    }
  });
  make_unorganised(res.cloud);
  return res;
}

}  // namespace uwgrasp::cloud
