#include "uwgrasp/grasp/occlusion.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/lanes.hpp"

namespace uwgrasp::grasp {

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
// The bin of a normalised image coordinate: one multiplication, the same for the map and the
// queries (a division per coordinate was most of the check's time).
// floor without a libm call (SSE2 has no rounding instruction); coordinates beyond +-1e9 bins
// (a point almost in the camera's plane) land far outside any map.
int bin(float v, float inverse) {
  const float x = std::clamp(v * inverse, -1e9f, 1e9f);  // NaN stays NaN: next line gives 0 or
  if (!(x == x)) return std::numeric_limits<int>::min() / 2;  // ... here, outside the map
  const int i = static_cast<int>(x);
  return i - (x < static_cast<float>(i) ? 1 : 0);
}
}  // namespace

float DepthMap::at(float x, float y) const {
  const float inverse = 1.0f / resolution;
  return at_bin(bin(x, inverse), bin(y, inverse));
}

float DepthMap::at_bin(int u, int v) const {
  u -= u0, v -= v0;
  if (u < 0 || v < 0 || u >= width || v >= height) return kInf;
  return depth[std::size_t(v) * std::size_t(width) + std::size_t(u)];
}

std::pair<float, float> DepthMap::range(int ua, int ub, int va, int vb) const {
  ua = std::max(ua - u0, 0), ub = std::min(ub - u0, width - 1);
  va = std::max(va - v0, 0), vb = std::min(vb - v0, height - 1);
  if (ua > ub || va > vb) return {kInf, -kInf};
  // The level where the bins span at most two blocks each way.
  std::size_t l = 0;
  while ((ub >> l) - (ua >> l) > 1 || (vb >> l) - (va >> l) > 1) ++l;
  const Level& level = levels[l];
  float lo = kInf, hi = -kInf;
  for (int v = va >> l; v <= vb >> l; ++v)
    for (int u = ua >> l; u <= ub >> l; ++u) {
      const std::size_t k = std::size_t(v) * std::size_t(level.width) + std::size_t(u);
      lo = std::min(lo, level.lo[k]), hi = std::max(hi, level.hi[k]);
    }
  return {lo, hi};
}

namespace {
// Level 0 is the map itself; each level above halves both sides, down to a single block.
void add_levels(DepthMap& m) {
  DepthMap::Level base{m.width, m.height, m.depth, m.depth};
  for (float& h : base.hi) h = h == kInf ? -kInf : h;
  m.levels.push_back(std::move(base));
  while (m.levels.back().width > 1 || m.levels.back().height > 1) {
    const DepthMap::Level& a = m.levels.back();
    DepthMap::Level b{(a.width + 1) / 2, (a.height + 1) / 2, {}, {}};
    b.lo.assign(std::size_t(b.width) * std::size_t(b.height), kInf);
    b.hi.assign(b.lo.size(), -kInf);
    for (int v = 0; v < a.height; ++v)
      for (int u = 0; u < a.width; ++u) {
        const std::size_t from = std::size_t(v) * std::size_t(a.width) + std::size_t(u);
        const std::size_t to = std::size_t(v / 2) * std::size_t(b.width) + std::size_t(u / 2);
        b.lo[to] = std::min(b.lo[to], a.lo[from]), b.hi[to] = std::max(b.hi[to], a.hi[from]);
      }
    m.levels.push_back(std::move(b));
  }
}
}  // namespace

DepthMap make_depth_map(std::span<const Eigen::Vector3f> pts, float resolution) {
  if (!(resolution > 0.0f)) throw Error("grasp.occlusion.resolution must be positive");
  DepthMap m;
  m.resolution = resolution;
  const float inverse = 1.0f / resolution;
  // Each point's bin once (points behind the camera cannot occlude anything in front of it).
  std::vector<Eigen::Vector3i> bins;  // u, v, index
  bins.reserve(pts.size());
  int u1 = std::numeric_limits<int>::min(), v1 = u1;
  m.u0 = m.v0 = std::numeric_limits<int>::max();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector3f& p = pts[i];
    if (!(p.z() > 0.0f)) continue;
    const float iz = 1.0f / p.z();
    const int u = bin(p.x() * iz, inverse), v = bin(p.y() * iz, inverse);
    bins.emplace_back(u, v, int(i));
    // Two bins of margin: the dilation reaches one bin out, the outermost ring stays empty.
    m.u0 = std::min(m.u0, u - 2), m.v0 = std::min(m.v0, v - 2);
    u1 = std::max(u1, u + 2), v1 = std::max(v1, v + 2);
  }
  if (bins.empty()) return m;  // nothing in front of the camera: an empty map
  m.width = u1 - m.u0 + 1, m.height = v1 - m.v0 + 1;
  if (double(m.width) * m.height > 5e7) throw Error("grasp.occlusion.resolution is too fine for this object");
  std::vector<float> raw(std::size_t(m.width) * m.height, kInf);
  for (const Eigen::Vector3i& b : bins) {
    float& d = raw[std::size_t(b.y() - m.v0) * m.width + std::size_t(b.x() - m.u0)];
    d = std::min(d, pts[std::size_t(b.z())].z());
  }
  // Dilated by one bin: the minimum over 3 x 3, as a row pass then a column pass.
  std::vector<float> rows(raw.size(), kInf);
  for (int v = 0; v < m.height; ++v)
    for (int u = 1; u + 1 < m.width; ++u) {
      const float* r = &raw[std::size_t(v) * m.width + u];
      rows[std::size_t(v) * m.width + u] = std::min({r[-1], r[0], r[1]});
    }
  m.depth.assign(raw.size(), kInf);
  for (int v = 1; v + 1 < m.height; ++v)
    for (int u = 1; u + 1 < m.width; ++u) {
      const std::size_t k = std::size_t(v) * m.width + u;
      m.depth[k] = std::min({rows[k - m.width], rows[k], rows[k + m.width]});
    }
  add_levels(m);
  return m;
}

namespace {
// Appends one patch: its samples padded to a multiple of four, and their bounds.
void add_patch(PartSamples& out, std::span<const Eigen::Vector3f> patch) {
  PartSamples::Patch p;
  p.begin = static_cast<std::uint32_t>(out.x.size());
  p.bounds.lo = p.bounds.hi = patch.front();
  for (std::size_t k = 0; k < (patch.size() + 3) / 4 * 4; ++k) {
    const Eigen::Vector3f& q = patch[std::min(k, patch.size() - 1)];
    out.x.push_back(q.x()), out.y.push_back(q.y()), out.z.push_back(q.z());
    p.bounds.lo = p.bounds.lo.cwiseMin(q), p.bounds.hi = p.bounds.hi.cwiseMax(q);
  }
  p.end = static_cast<std::uint32_t>(out.x.size());
  out.patches.push_back(p);
}

// Samples per patch side: 4 x 4 patches (23 on the default gripper) halved the time of the
// occlusion tests on the barbell; 2 x 2 patches cost as much to clear as their samples cost to
// test; one patch per part rarely clears.
constexpr int kPatch = 4;

// Samples on the faces of box b at about `spacing`, as patches of kPatch x kPatch samples (the
// last sample along an axis joins the cell before it).
void add_box(PartSamples& out, const Box& b, float spacing) {
  const Eigen::Vector3f size = b.hi - b.lo;
  Eigen::Vector3i n, cells;
  for (int a = 0; a < 3; ++a) {
    n[a] = std::max(1, int(std::ceil(size[a] / spacing)));
    cells[a] = (n[a] + kPatch - 1) / kPatch;
  }
  // Sample indices [first, last] of cell c along axis a.
  const auto first = [&](int c) { return c * kPatch; };
  const auto last = [&](int a, int c) { return c + 1 == cells[a] ? n[a] : (c + 1) * kPatch - 1; };
  std::vector<Eigen::Vector3f> patch;
  for (int ci = 0; ci < cells.x(); ++ci)
    for (int cj = 0; cj < cells.y(); ++cj)
      for (int ck = 0; ck < cells.z(); ++ck) {
        patch.clear();
        for (int i = first(ci); i <= last(0, ci); ++i)
          for (int j = first(cj); j <= last(1, cj); ++j)
            for (int k = first(ck); k <= last(2, ck); ++k) {
              const bool surface = i == 0 || j == 0 || k == 0 || i == n.x() || j == n.y() || k == n.z();
              if (surface)
                patch.push_back(b.lo + size.cwiseProduct(Eigen::Vector3f(float(i) / n.x(), float(j) / n.y(),
                                                                         float(k) / n.z())));
            }
        if (!patch.empty()) add_patch(out, patch);
      }
}
}  // namespace

PartSamples part_samples(const Gripper& g, float spacing) {
  if (!(spacing > 0.0f)) throw Error("grasp.occlusion.spacing must be positive");
  PartSamples out;
  for (const Box& b : g.solids) add_box(out, b, spacing);
  return out;
}

namespace {
// bin() on four lanes.
lanes::M4 bins(lanes::F4 v, float inverse) {
  const lanes::F4 x = v * inverse;
  const lanes::F4 c = x < -1e9f ? lanes::splat(-1e9f) : (x > 1e9f ? lanes::splat(1e9f) : x);
  const lanes::M4 i = __builtin_convertvector(c, lanes::M4);
  return i + (c < __builtin_convertvector(i, lanes::F4));  // true is -1: one bin down
}
}  // namespace

namespace {
struct Placed {
  const DepthMap& map;
  const OcclusionConfig& cfg;
  Eigen::Matrix3f R;  // gripper to camera
  Eigen::Vector3f t;
  float inverse;      // 1 / map resolution

  // Camera-frame depth and bins of four gripper-frame points.
  lanes::F4 depth(const lanes::V3& s) const { return R(2, 0) * s.x + R(2, 1) * s.y + R(2, 2) * s.z + t.z(); }
  lanes::M4 u(const lanes::V3& s, lanes::F4 iz) const {
    return bins((R(0, 0) * s.x + R(0, 1) * s.y + R(0, 2) * s.z + t.x()) * iz, inverse);
  }
  lanes::M4 v(const lanes::V3& s, lanes::F4 iz) const {
    return bins((R(1, 0) * s.x + R(1, 1) * s.y + R(1, 2) * s.z + t.y()) * iz, inverse);
  }

  // True when no sample in the box can be in the band: all corners in front of the camera
  // bound the box's image (perspective keeps it in their hull) and its depths, so the map's
  // depth range over that image, one bin wider for rounding, bounds every sample's `behind`.
  bool clear(const Box& b) const {
    const lanes::F4 xs{b.lo.x(), b.hi.x(), b.lo.x(), b.hi.x()}, ys{b.lo.y(), b.lo.y(), b.hi.y(), b.hi.y()};
    const lanes::V3 near{xs, ys, lanes::splat(b.lo.z())}, far{xs, ys, lanes::splat(b.hi.z())};
    const lanes::F4 z0 = depth(near), z1 = depth(far);
    if (lanes::bits((z0 > 0.0f) & (z1 > 0.0f)) != 15) return false;
    const lanes::F4 i0 = 1.0f / z0, i1 = 1.0f / z1;
    const lanes::M4 ua = u(near, i0), ub = u(far, i1), va = v(near, i0), vb = v(far, i1);
    int ulo = ua[0], uhi = ua[0], vlo = va[0], vhi = va[0];
    float zlo = z0[0], zhi = z0[0];
    for (int l = 0; l < 4; ++l) {
      ulo = std::min({ulo, ua[l], ub[l]}), uhi = std::max({uhi, ua[l], ub[l]});
      vlo = std::min({vlo, va[l], vb[l]}), vhi = std::max({vhi, va[l], vb[l]});
      zlo = std::min({zlo, z0[l], z1[l]}), zhi = std::max({zhi, z0[l], z1[l]});
    }
    const auto [dlo, dhi] = map.range(ulo - 1, uhi + 1, vlo - 1, vhi + 1);
    constexpr float kPad = 1e-5f;  // m: the samples' own rounding
    return zhi + kPad - dlo <= cfg.tolerance || zlo - kPad - dhi >= cfg.thickness;
  }

  bool any(const PartSamples& s, const PartSamples::Patch& p) const {
    for (std::uint32_t k = p.begin; k < p.end; k += 4) {
      const lanes::V3 q = lanes::load(&s.x[k], &s.y[k], &s.z[k]);
      const lanes::F4 qz = depth(q);
      const int front = lanes::bits(qz > 0.0f);
      if (front == 0) continue;
      const lanes::F4 iz = 1.0f / qz;
      const lanes::M4 us = u(q, iz), vs = v(q, iz);
      for (int f = front; f != 0; f &= f - 1) {
        const int l = std::countr_zero(unsigned(f));
        const float behind = qz[l] - map.at_bin(us[l], vs[l]);
        if (behind > cfg.tolerance && behind < cfg.thickness) return true;
      }
    }
    return false;
  }
};
}  // namespace

bool occluded(const DepthMap& map, const PartSamples& samples, const Candidate& c,
              const Pose& camera_from_level, const OcclusionConfig& cfg, bool cull) {
  if (map.depth.empty()) return false;
  const Placed placed{map, cfg, camera_from_level.linear().cast<float>() * c.rotation,
                      (camera_from_level * c.position.cast<double>()).cast<float>(), 1.0f / map.resolution};
  for (const PartSamples::Patch& p : samples.patches)
    if (!(cull && placed.clear(p.bounds)) && placed.any(samples, p)) return true;
  return false;
}

}  // namespace uwgrasp::grasp
