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
  return m;
}

std::vector<Eigen::Vector3f> part_samples(const Gripper& g, float spacing) {
  if (!(spacing > 0.0f)) throw Error("grasp.occlusion.spacing must be positive");
  std::vector<Eigen::Vector3f> out;
  for (const Box& b : g.solids) {
    const Eigen::Vector3f size = b.hi - b.lo;
    Eigen::Vector3i n;
    for (int a = 0; a < 3; ++a) n[a] = std::max(1, int(std::ceil(size[a] / spacing)));
    for (int i = 0; i <= n.x(); ++i)
      for (int j = 0; j <= n.y(); ++j)
        for (int k = 0; k <= n.z(); ++k) {
          const bool surface = i == 0 || j == 0 || k == 0 || i == n.x() || j == n.y() || k == n.z();
          if (!surface) continue;
          out.push_back(b.lo + size.cwiseProduct(Eigen::Vector3f(float(i) / n.x(), float(j) / n.y(),
                                                                 float(k) / n.z())));
        }
  }
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

bool occluded(const DepthMap& map, std::span<const Eigen::Vector3f> samples, const Candidate& c,
              const Pose& camera_from_level, const OcclusionConfig& cfg) {
  if (map.depth.empty()) return false;
  const Eigen::Matrix3f R = camera_from_level.linear().cast<float>() * c.rotation;
  const Eigen::Vector3f t =
      (camera_from_level * c.position.cast<double>()).cast<float>();
  const float inverse = 1.0f / map.resolution;
  // Four samples at a time; the last group repeats the last sample.
  for (std::size_t k = 0; k < samples.size(); k += 4) {
    float xs[4], ys[4], zs[4];
    for (std::size_t l = 0; l < 4; ++l) {
      const Eigen::Vector3f& p = samples[std::min(k + l, samples.size() - 1)];
      xs[l] = p.x(), ys[l] = p.y(), zs[l] = p.z();
    }
    const lanes::V3 s{lanes::load(xs), lanes::load(ys), lanes::load(zs)};
    const lanes::F4 qz = R(2, 0) * s.x + R(2, 1) * s.y + R(2, 2) * s.z + t.z();
    const int front = lanes::bits(qz > 0.0f);
    if (front == 0) continue;
    const lanes::F4 iz = 1.0f / qz;
    const lanes::M4 u = bins((R(0, 0) * s.x + R(0, 1) * s.y + R(0, 2) * s.z + t.x()) * iz, inverse);
    const lanes::M4 v = bins((R(1, 0) * s.x + R(1, 1) * s.y + R(1, 2) * s.z + t.y()) * iz, inverse);
    for (int f = front; f != 0; f &= f - 1) {
      const int l = std::countr_zero(unsigned(f));
      const float behind = qz[l] - map.at_bin(u[l], v[l]);
      if (behind > cfg.tolerance && behind < cfg.thickness) return true;
    }
  }
  return false;
}

}  // namespace uwgrasp::grasp
