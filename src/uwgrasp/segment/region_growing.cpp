#include "uwgrasp/segment/region_growing.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/cloud/radix_sort.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/segment/merge.hpp"

namespace uwgrasp::segment {

namespace {
float color_dist2(Rgb8 a, Rgb8 b) {
  const float dr = float(a.r) - float(b.r), dg = float(a.g) - float(b.g),
              db = float(a.b) - float(b.b);
  return dr * dr + dg * dg + db * db;
}

void check_inputs(const Cloud& c, const RegionConfig& r, const ColorConfig& col) {
  if (!c.has_normals() || !c.has_curvature())
    throw Error("region growing needs normals and curvature (compute normals first)");
  if (col.enabled && !c.has_colors())
    throw Error("colour region growing needs an RGB cloud (segment.color.enabled = true)");
  if (r.k < 2) throw Error("segment.region.k must be at least 2, got " + std::to_string(r.k));
}

// The first k entries of each list (lists are nearest first).
cloud::Neighbours truncate(const cloud::Neighbours& in, std::size_t k) {
  if (in.k <= k) return in;
  cloud::Neighbours out;
  out.k = k;
  const std::size_t n = in.count.size();
  out.indices.resize(n * k), out.sq_dists.resize(n * k), out.count.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.count[i] = std::min<std::uint32_t>(in.count[i], std::uint32_t(k));
    std::copy_n(&in.indices[i * in.k], out.count[i], &out.indices[i * k]);
    std::copy_n(&in.sq_dists[i * in.k], out.count[i], &out.sq_dists[i * k]);
  }
  return out;
}

// Orders floats as unsigned integers: the sign bit set on positives, every bit flipped on
// negatives; -0 is made +0 first, so equal values get equal keys.
std::uint32_t ordered_bits(float v) {
  const auto b = std::bit_cast<std::uint32_t>(v + 0.0f);
  return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}

// Seed order: points with a finite normal by ascending curvature, ties by index - a stable radix
// sort on the curvature's ordered bits above the point index.
// Into scratch.order.
void seed_order(const Cloud& c, RegionScratch& scratch) {
  std::vector<std::uint64_t>& items = scratch.seeds;
  items.clear();
  items.reserve(c.size());
  for (std::size_t i = 0; i < c.size(); ++i)
    if (is_finite(c.normals[i]) && std::isfinite(c.curvature[i]))
      items.push_back(std::uint64_t(ordered_bits(c.curvature[i])) << 32 | i);
  cloud::radix_sort(items, 32, 32, scratch.sort);
  scratch.order.resize(items.size());
  for (std::size_t j = 0; j < items.size(); ++j)
    scratch.order[j] = static_cast<std::uint32_t>(items[j]);
}

struct Grower {
  const Cloud& c;
  const cloud::Neighbours& nb;
  const RegionConfig& r;
  const ColorConfig& col;
  float cos_angle, dist2, color2;
  std::vector<std::int32_t>& label;
  std::vector<std::uint32_t>& queue;

  bool joins(std::uint32_t from, std::uint32_t seed, std::uint32_t q, float d2) const {
    if (dist2 > 0.0f && d2 > dist2) return false;
    const Eigen::Vector3f& ref = r.smooth_mode ? c.normals[from] : c.normals[seed];
    if (!(std::abs(ref.dot(c.normals[q])) >= cos_angle)) return false;  // NaN normals fail
    if (col.enabled && color_dist2(c.colors[from], c.colors[q]) > color2) return false;
    return true;
  }

  void grow(std::uint32_t seed, std::int32_t id) {
    queue.clear();
    queue.push_back(seed);
    label[seed] = id;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::uint32_t from = queue[head];
      const auto idx = nb.of(from);
      const auto d2 = nb.dists_of(from);
      for (std::size_t j = 0; j < idx.size(); ++j) {
        const std::uint32_t q = idx[j];
        if (label[q] != -1 || !joins(from, seed, q, d2[j])) continue;
        label[q] = id;
        if (c.curvature[q] < r.curvature) queue.push_back(q);
      }
    }
  }
};
}  // namespace

Segmentation grow_regions(const Cloud& cloud, const RegionConfig& region,
                          const ColorConfig& color) {
  if (cloud.empty()) return {};
  check_inputs(cloud, region, color);
  const cloud::KdTree tree(cloud.points);
  return grow_regions(cloud, region, color,
                      cloud::knn_all(tree, cloud.points, std::min<std::size_t>(region.k, cloud.size())));
}

Segmentation grow_regions(const Cloud& cloud, const RegionConfig& region,
                          const ColorConfig& color, const cloud::Neighbours& all) {
  Segmentation out;
  RegionScratch scratch;
  grow_regions(cloud, region, color, all, out, scratch);
  return out;
}

namespace {
// Keeps regions within [min_size, max_size], numbered in order of their first seed; the
// segments' lists reuse the capacity a previous frame left them.
void keep_sized(std::size_t points, std::uint32_t n, const RegionConfig& region, Segmentation& out,
                RegionScratch& scratch) {
  std::vector<std::uint32_t>& size = scratch.size;
  size.assign(n, 0);
  for (auto l : out.label)
    if (l >= 0) ++size[static_cast<std::size_t>(l)];
  std::vector<std::int32_t>& renum = scratch.renumber;
  renum.assign(n, -1);
  const auto kept = [&](std::uint32_t k) { return k >= region.min_size && k <= region.max_size; };
  std::size_t m = 0;
  for (std::uint32_t s = 0; s < n; ++s)
    if (kept(size[s])) renum[s] = static_cast<std::int32_t>(m++);
  // Lists beyond this frame's count wait in scratch.spare with their capacity, for a later frame
  // with more segments.
  while (out.segments.size() > m) {
    scratch.spare.push_back(std::move(out.segments.back()));
    out.segments.pop_back();
  }
  while (out.segments.size() < m && !scratch.spare.empty()) {
    out.segments.push_back(std::move(scratch.spare.back()));
    scratch.spare.pop_back();
  }
  out.segments.resize(m);
  for (std::uint32_t s = 0; s < n; ++s)
    if (renum[s] >= 0) {
      auto& segment = out.segments[static_cast<std::size_t>(renum[s])];
      segment.clear();
      segment.reserve(size[s]);  // its size is known: at most one allocation
    }
  for (std::size_t i = 0; i < points; ++i) {
    auto& l = out.label[i];
    if (l < 0) continue;
    l = renum[static_cast<std::size_t>(l)];
    if (l >= 0) out.segments[static_cast<std::size_t>(l)].push_back(static_cast<std::uint32_t>(i));
  }
}
}  // namespace

void grow_regions(const Cloud& cloud, const RegionConfig& region, const ColorConfig& color,
                  const cloud::Neighbours& all, Segmentation& out, RegionScratch& scratch) {
  if (cloud.empty()) {
    out.label.clear(), out.segments.clear();
    return;
  }
  check_inputs(cloud, region, color);
  if (all.count.size() != cloud.size() ||
      (!all.window && all.k < region.k && all.k < cloud.size()))
    throw Error("region growing: the shared neighbour lists do not fit this cloud");
  out.label.assign(cloud.size(), -1);
  // Only when the shared kNN rows are longer than k; an organised frame's window lists are used
  // whole (the window is the neighbourhood).
  cloud::Neighbours cut;
  const cloud::Neighbours& nb =
      !all.window && all.k > region.k ? (cut = truncate(all, region.k)) : all;
  const float rad = region.angle_deg * std::numbers::pi_v<float> / 180.0f;
  Grower g{cloud,
           nb,
           region,
           color,
           std::cos(rad),
           region.distance * region.distance,
           color.point_threshold * color.point_threshold,
           out.label,
           scratch.queue};
  g.queue.reserve(cloud.size());  // once, not a doubling per region that outgrows the last
  std::int32_t count = 0;
  seed_order(cloud, scratch);
  for (std::uint32_t s : scratch.order)
    if (out.label[s] == -1) g.grow(s, count++);

  std::uint32_t n = static_cast<std::uint32_t>(count);
  if (color.enabled) n = merge_regions(cloud, nb, out.label, n, region, color);
  keep_sized(cloud.size(), n, region, out, scratch);
}

}  // namespace uwgrasp::segment
