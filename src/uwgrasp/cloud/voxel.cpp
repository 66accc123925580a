#include "uwgrasp/cloud/voxel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <unordered_map>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

namespace {
constexpr std::uint64_t kNoKey = std::numeric_limits<std::uint64_t>::max();

// Open-addressing map from voxel key to a dense slot number, in first-seen order.
class SlotTable {
 public:
  explicit SlotTable(std::size_t n) : mask_(std::bit_ceil(std::max<std::size_t>(16, 2 * n)) - 1) {
    keys_.assign(mask_ + 1, kNoKey);
    slots_.resize(mask_ + 1);
  }
  std::uint32_t slot(std::uint64_t key) {
    std::size_t h = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 20) & mask_;
    while (keys_[h] != kNoKey && keys_[h] != key) h = (h + 1) & mask_;
    if (keys_[h] == kNoKey) {
      keys_[h] = key;
      slots_[h] = static_cast<std::uint32_t>(order_.size());
      order_.push_back(key);
    }
    return slots_[h];
  }
  const std::vector<std::uint64_t>& keys_in_order() const { return order_; }

 private:
  std::size_t mask_;
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> slots_;
  std::vector<std::uint64_t> order_;
};

struct Accum {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  double curv = 0.0;
  std::uint32_t rgb[3] = {0, 0, 0};
  std::uint32_t count = 0;
};

std::uint32_t majority(std::vector<std::uint32_t>& labels) {
  std::sort(labels.begin(), labels.end());
  std::uint32_t best = labels.front(), run = 0, best_run = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    run = (i > 0 && labels[i] == labels[i - 1]) ? run + 1 : 1;
    if (run > best_run) best_run = run, best = labels[i];
  }
  return best;
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
  const std::vector<std::uint64_t> keys = voxel_keys(in, cfg.leaf);
  SlotTable table(in.size());
  std::vector<std::uint32_t> slot_of(in.size(), VoxelResult::kDropped);
  std::uint64_t last_key = kNoKey;
  std::uint32_t last_slot = 0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (keys[i] == kNoKey) continue;
    if (keys[i] != last_key) last_key = keys[i], last_slot = table.slot(keys[i]);  // scans are coherent
    slot_of[i] = last_slot;
  }
  const std::size_t nslots = table.keys_in_order().size();
  std::vector<Accum> acc(nslots);
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> labels;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const std::uint32_t s = slot_of[i];
    if (s == VoxelResult::kDropped) continue;
    Accum& a = acc[s];
    a.p += in.points[i].cast<double>();
    if (in.has_normals() && is_finite(in.normals[i])) a.n += in.normals[i].cast<double>();
    if (in.has_curvature() && std::isfinite(in.curvature[i])) a.curv += in.curvature[i];
    if (in.has_colors()) a.rgb[0] += in.colors[i].r, a.rgb[1] += in.colors[i].g, a.rgb[2] += in.colors[i].b;
    if (in.has_labels()) labels[s].push_back(in.labels[i]);
    ++a.count;
  }
  // Output order: by voxel key, as PCL's sorted voxel indices.
  std::vector<std::uint32_t> order(nslots);
  std::iota(order.begin(), order.end(), 0u);
  const auto& skeys = table.keys_in_order();
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return skeys[a] < skeys[b]; });
  std::vector<std::uint32_t> out_of_slot(nslots, VoxelResult::kDropped);
  VoxelResult res;
  Cloud& out = res.cloud;
  out.viewpoint = in.viewpoint;
  for (std::uint32_t s : order) {
    const Accum& a = acc[s];
    if (a.count < std::max<std::uint32_t>(1, cfg.min_points)) continue;
    out_of_slot[s] = static_cast<std::uint32_t>(out.points.size());
    const double c = a.count;
    out.points.push_back((a.p / c).cast<float>());
    if (in.has_normals()) {
      const double len = a.n.norm();
      out.normals.push_back(len > 0 ? Eigen::Vector3f((a.n / len).cast<float>())
                                    : Eigen::Vector3f::Constant(std::nanf("")));
    }
    if (in.has_curvature()) out.curvature.push_back(static_cast<float>(a.curv / c));
    if (in.has_colors()) {
      auto avg = [&](int ch) { return static_cast<std::uint8_t>(std::lround(a.rgb[ch] / c)); };
      out.colors.push_back({avg(0), avg(1), avg(2)});
    }
    if (in.has_labels()) out.labels.push_back(majority(labels[s]));
  }
  make_unorganised(out);
  res.voxel_of.resize(in.size(), VoxelResult::kDropped);
  for (std::size_t i = 0; i < in.size(); ++i)
    if (slot_of[i] != VoxelResult::kDropped) res.voxel_of[i] = out_of_slot[slot_of[i]];
  return res;
}

}  // namespace uwgrasp::cloud
