#include "uwgrasp/cloud/voxel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <span>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/cloud/radix_sort.hpp"

namespace uwgrasp::cloud {

namespace {
// Every pass over the points works on fixed chunks, so sums and orders do not depend on the
// thread count.
constexpr std::size_t kChunk = std::size_t(1) << 14;

std::size_t chunk_count(std::size_t n) { return (n + kChunk - 1) / kChunk; }

template <class F>
void for_chunks(std::size_t n, F&& f) {
  tbb::parallel_for(std::size_t(0), chunk_count(n), [&](std::size_t c) {
    f(c, c * kChunk, std::min(n, (c + 1) * kChunk));
  });
}

// floor(v) for |v| < 2^62 without a libm call (SSE2 has no rounding instruction).
std::int64_t floor_int(float v) {
  const auto t = static_cast<std::int64_t>(v);
  return t - std::int64_t(static_cast<float>(t) > v);
}

// PCL's voxel indexing: cell floor(p * (1/leaf)) in single precision, numbered x fastest from
// the cell of the cloud's minimum. Items pack the voxel number above the point index.
struct Grid {
  float inv = 0.0f;
  std::int64_t min_b[3] = {0, 0, 0};
  std::uint64_t dx = 0, dxy = 0;
  int index_bits = 0, key_bits = 0;

  std::uint64_t item(const Eigen::Vector3f& p, std::size_t i) const {
    const auto ix = std::uint64_t(floor_int(p.x() * inv) - min_b[0]);
    const auto iy = std::uint64_t(floor_int(p.y() * inv) - min_b[1]);
    const auto iz = std::uint64_t(floor_int(p.z() * inv) - min_b[2]);
    return ((ix + iy * dx + iz * dxy) << index_bits) | i;
  }
  std::uint32_t index(std::uint64_t item) const {
    return std::uint32_t(item & ((std::uint64_t(1) << index_bits) - 1));
  }
  std::uint64_t key(std::uint64_t item) const { return item >> index_bits; }
};

struct Span {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(INFINITY), hi = Eigen::Vector3f::Constant(-INFINITY);
  std::size_t finite = 0;
};

// The bounds of the finite points and the finite count of every chunk.
std::vector<Span> chunk_spans(const Cloud& in) {
  std::vector<Span> spans(chunk_count(in.size()));
  for_chunks(in.size(), [&](std::size_t c, std::size_t a, std::size_t b) {
    Span s;
    for (std::size_t i = a; i < b; ++i)
      if (is_finite(in.points[i])) s.lo = s.lo.cwiseMin(in.points[i]), s.hi = s.hi.cwiseMax(in.points[i]), ++s.finite;
    spans[c] = s;
  });
  return spans;
}

Grid make_grid(const Span& all, float leaf, std::size_t n) {
  Grid g;
  g.inv = 1.0f / leaf;
  g.index_bits = std::max(1, int(std::bit_width(n - 1)));
  double cells = 1.0;
  for (int a = 0; a < 3; ++a) {
    const float lo = all.lo[a] * g.inv, hi = all.hi[a] * g.inv;
    if (!(std::abs(lo) < 4.0e18f && std::abs(hi) < 4.0e18f))
      throw Error("voxel grid: coordinates up to " + std::to_string(std::max(std::abs(all.lo[a]), std::abs(all.hi[a]))) +
                  " m are too large for a leaf of " + std::to_string(leaf) + " m");
    g.min_b[a] = floor_int(lo);
    cells *= double(floor_int(hi) - g.min_b[a] + 1);
  }
  g.dx = std::uint64_t(floor_int(all.hi.x() * g.inv) - g.min_b[0] + 1);
  g.dxy = g.dx * std::uint64_t(floor_int(all.hi.y() * g.inv) - g.min_b[1] + 1);
  g.key_bits = std::max(1, int(std::ceil(std::log2(cells))));
  if (g.key_bits + g.index_bits > 64)
    throw Error("voxel grid: leaf " + std::to_string(leaf) +
                " m is too small for a cloud this large (voxel indices would overflow)");
  return g;
}

// The packed item of every finite point, in point order. The buffer is left uninitialised so
// that the parallel chunks, not one memset, touch its pages first.
struct Items {
  std::unique_ptr<std::uint64_t[]> data;
  std::size_t size = 0;
  std::span<std::uint64_t> all() const { return {data.get(), size}; }
};

Items make_items(const Cloud& in, const Grid& g, const std::vector<Span>& spans) {
  std::vector<std::size_t> at(spans.size() + 1, 0);
  for (std::size_t c = 0; c < spans.size(); ++c) at[c + 1] = at[c] + spans[c].finite;
  Items items{std::unique_ptr<std::uint64_t[]>(new std::uint64_t[at.back()]), at.back()};
  for_chunks(in.size(), [&](std::size_t c, std::size_t a, std::size_t b) {
    std::uint64_t* out = items.data.get() + at[c];
    if (spans[c].finite == b - a) {  // the usual chunk: no test, no branch
      for (std::size_t i = a; i < b; ++i) out[i - a] = g.item(in.points[i], i);
      return;
    }
    for (std::size_t i = a; i < b; ++i)
      if (is_finite(in.points[i])) *out++ = g.item(in.points[i], i);
  });
  return items;
}

// Calls f(run) for every run of equal keys (one voxel) that starts in items [a, b) and has at
// least min_points items, in order. A run may end past b; one that began before a is skipped,
// so chunks of the sorted items see every run exactly once.
template <class F>
void runs_from(std::span<const std::uint64_t> items, const Grid& g, std::size_t a, std::size_t b,
               std::uint32_t min_points, F&& f) {
  std::size_t j = a;
  while (j < b && j > 0 && g.key(items[j]) == g.key(items[j - 1])) ++j;
  while (j < b) {
    const std::uint64_t key = g.key(items[j]);
    std::size_t e = j + 1;
    while (e < items.size() && g.key(items[e]) == key) ++e;
    if (e - j >= min_points) f(items.subspan(j, e - j));
    j = e;
  }
}

std::uint32_t majority(std::vector<std::uint32_t>& labels) {
  std::sort(labels.begin(), labels.end());
  std::uint32_t best = labels.front(), run = 0, best_run = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    run = (i > 0 && labels[i] == labels[i - 1]) ? run + 1 : 1;
    if (run > best_run) best_run = run, best = labels[i];
  }
  return best;
}

// Writes the centroid of the points of one run of items (every attribute the cloud has) to
// slot o of `out`, whose attribute vectors are already sized. Sums in double, in sorted order.
void centroid_into(const Cloud& in, const Grid& g, std::span<const std::uint64_t> run, Cloud& out,
                   std::size_t o) {
  const double c = double(run.size());
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (const std::uint64_t it : run) p += in.points[g.index(it)].cast<double>();
  out.points[o] = (p / c).cast<float>();
  if (in.has_normals()) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (const std::uint64_t it : run)
      if (is_finite(in.normals[g.index(it)])) n += in.normals[g.index(it)].cast<double>();
    const double len = n.norm();
    out.normals[o] = len > 0 ? Eigen::Vector3f((n / len).cast<float>()) : Eigen::Vector3f::Constant(NAN);
  }
  if (in.has_curvature()) {
    double curv = 0.0;
    for (const std::uint64_t it : run)
      if (std::isfinite(in.curvature[g.index(it)])) curv += in.curvature[g.index(it)];
    out.curvature[o] = static_cast<float>(curv / c);
  }
  if (in.has_colors()) {
    std::uint64_t rgb[3] = {0, 0, 0};
    for (const std::uint64_t it : run) {
      const Rgb8 col = in.colors[g.index(it)];
      rgb[0] += col.r, rgb[1] += col.g, rgb[2] += col.b;
    }
    // The mean rounded half up, in integers: floor(s / m + 1/2) = floor((2s + m) / 2m).
    const std::uint64_t m = run.size();
    const auto avg = [&](int ch) { return static_cast<std::uint8_t>((2 * rgb[ch] + m) / (2 * m)); };
    out.colors[o] = {avg(0), avg(1), avg(2)};
  }
  if (in.has_labels()) {
    std::vector<std::uint32_t> labels;
    for (const std::uint64_t it : run) labels.push_back(in.labels[g.index(it)]);
    out.labels[o] = majority(labels);
  }
}

// Sizes every attribute the input has to n slots.
void size_like(const Cloud& in, std::size_t n, Cloud& out) {
  out.points.assign(n, Eigen::Vector3f::Zero());
  if (in.has_normals()) out.normals.assign(n, Eigen::Vector3f::Zero());
  if (in.has_curvature()) out.curvature.assign(n, 0.0f);
  if (in.has_colors()) out.colors.assign(n, Rgb8{});
  if (in.has_labels()) out.labels.assign(n, 0u);
}
}  // namespace

VoxelResult voxel_grid(const Cloud& in, const VoxelConfig& cfg) {
  if (!(cfg.leaf > 0.0f) || !std::isfinite(cfg.leaf))
    throw Error("voxel grid: leaf must be > 0, got " + std::to_string(cfg.leaf));
  VoxelResult res;
  res.voxel_of.assign(in.size(), VoxelResult::kDropped);
  res.cloud.viewpoint = in.viewpoint;
  res.cloud.orientation = in.orientation;
  const std::vector<Span> spans = chunk_spans(in);
  Span all;
  for (const Span& s : spans) all.lo = all.lo.cwiseMin(s.lo), all.hi = all.hi.cwiseMax(s.hi), all.finite += s.finite;
  if (all.finite == 0) {
    size_like(in, 0, res.cloud);
    make_unorganised(res.cloud);
    return res;
  }
  const Grid g = make_grid(all, cfg.leaf, in.size());
  const Items items = make_items(in, g, spans);
  radix_sort(items.all(), g.index_bits, g.key_bits);
  // Each run of equal keys is one voxel, already in PCL's order (ascending voxel number). The
  // kept runs are counted per chunk of the sorted items, then each chunk writes its centroids
  // from its first output slot on, in parallel.
  const std::span<const std::uint64_t> sorted = items.all();
  const std::uint32_t min_points = std::max<std::uint32_t>(1, cfg.min_points);
  std::vector<std::size_t> at(chunk_count(sorted.size()) + 1, 0);
  for_chunks(sorted.size(), [&](std::size_t c, std::size_t a, std::size_t b) {
    std::size_t count = 0;  // local: neighbouring chunks' slots share a cache line
    runs_from(sorted, g, a, b, min_points, [&](auto) { ++count; });
    at[c + 1] = count;
  });
  for (std::size_t c = 1; c < at.size(); ++c) at[c] += at[c - 1];
  size_like(in, at.back(), res.cloud);
  for_chunks(sorted.size(), [&](std::size_t c, std::size_t a, std::size_t b) {
    std::size_t o = at[c];
    runs_from(sorted, g, a, b, min_points, [&](std::span<const std::uint64_t> run) {
      for (const std::uint64_t it : run) res.voxel_of[g.index(it)] = std::uint32_t(o);
      centroid_into(in, g, run, res.cloud, o++);
    });
  });
  make_unorganised(res.cloud);
  return res;
}

}  // namespace uwgrasp::cloud
