#include "uwgrasp/grasp/occlusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::grasp {

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
int bin(float v, float res) { return static_cast<int>(std::floor(v / res)); }
}  // namespace

float DepthMap::at(float x, float y) const {
  const int u = bin(x, resolution) - u0, v = bin(y, resolution) - v0;
  if (u < 0 || v < 0 || u >= width || v >= height) return kInf;
  return depth[std::size_t(v) * std::size_t(width) + std::size_t(u)];
}

DepthMap make_depth_map(std::span<const Eigen::Vector3f> pts, float resolution) {
  if (!(resolution > 0.0f)) throw Error("grasp.occlusion.resolution must be positive");
  DepthMap m;
  m.resolution = resolution;
  int u1 = std::numeric_limits<int>::min(), v1 = u1;
  m.u0 = m.v0 = std::numeric_limits<int>::max();
  for (const auto& p : pts) {
    if (!(p.z() > 0.0f)) continue;  // behind the camera: cannot occlude anything in front
    const int u = bin(p.x() / p.z(), resolution), v = bin(p.y() / p.z(), resolution);
    m.u0 = std::min(m.u0, u - 1), m.v0 = std::min(m.v0, v - 1);
    u1 = std::max(u1, u + 1), v1 = std::max(v1, v + 1);
  }
  if (u1 < m.u0) return m;  // nothing in front of the camera: an empty map
  m.width = u1 - m.u0 + 1, m.height = v1 - m.v0 + 1;
  if (double(m.width) * m.height > 5e7) throw Error("grasp.occlusion.resolution is too fine for this object");
  std::vector<float> raw(std::size_t(m.width) * m.height, kInf);
  for (const auto& p : pts) {
    if (!(p.z() > 0.0f)) continue;
    const int u = bin(p.x() / p.z(), resolution) - m.u0, v = bin(p.y() / p.z(), resolution) - m.v0;
    float& d = raw[std::size_t(v) * m.width + u];
    d = std::min(d, p.z());
  }
  m.depth.assign(raw.size(), kInf);
  for (int v = 1; v + 1 < m.height; ++v)
    for (int u = 1; u + 1 < m.width; ++u) {
      float d = kInf;
      for (int dv = -1; dv <= 1; ++dv)
        for (int du = -1; du <= 1; ++du) d = std::min(d, raw[std::size_t(v + dv) * m.width + (u + du)]);
      m.depth[std::size_t(v) * m.width + u] = d;
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

bool occluded(const DepthMap& map, std::span<const Eigen::Vector3f> samples, const Candidate& c,
              const Pose& camera_from_level, const OcclusionConfig& cfg) {
  if (map.depth.empty()) return false;
  const Eigen::Matrix3f R = camera_from_level.linear().cast<float>() * c.rotation;
  const Eigen::Vector3f t =
      (camera_from_level * c.position.cast<double>()).cast<float>();
  for (const auto& s : samples) {
    const Eigen::Vector3f q = R * s + t;
    if (!(q.z() > 0.0f)) continue;
    const float behind = q.z() - map.at(q.x() / q.z(), q.y() / q.z());
    if (behind > cfg.tolerance && behind < cfg.thickness) return true;
  }
  return false;
}

}  // namespace uwgrasp::grasp
