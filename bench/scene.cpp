#include "scene.hpp"

#include <array>
#include <cmath>
#include <limits>

#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::bench {

namespace {
struct Box {
  Eigen::Vector3f lo, hi;  // in the level frame: x right, y forward, z up, floor at z = 0
  Rgb8 color;
};

// Slab test; returns the entry distance or +inf, and the axis of the face entered.
float hit_box(const Box& b, const Eigen::Vector3f& o, const Eigen::Vector3f& d, int& face) {
  float t0 = 0, t1 = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / d[a];
    float ta = (b.lo[a] - o[a]) * inv, tb = (b.hi[a] - o[a]) * inv;
    if (ta > tb) std::swap(ta, tb);
    if (ta > t0) face = a;
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
  }
  return t0 <= t1 ? t0 : std::numeric_limits<float>::infinity();
}
}  // namespace

Cloud seafloor_scene(std::uint32_t width, std::uint32_t height, float noise, std::uint64_t seed,
                     std::vector<Eigen::Vector3f>* truth) {
  // Level frame L': x right, y forward, z up; camera 1.2 m above the floor, pitched 45 deg down.
  const float s = std::sqrt(0.5f), h = 1.2f;
  const Eigen::Vector3f cam(0, 0, h);
  Eigen::Matrix3f R;  // columns: optical x, y, z in the level frame
  R.col(0) = Eigen::Vector3f(1, 0, 0);
  R.col(2) = Eigen::Vector3f(0, s, -s);
  R.col(1) = R.col(2).cross(R.col(0));
  const std::array<Box, 4> boxes{{{{-0.35f, 1.3f, 0}, {-0.15f, 1.5f, 0.2f}, {200, 30, 30}},
                                  {{0.0f, 1.1f, 0}, {0.3f, 1.15f, 0.05f}, {30, 30, 200}},
                                  {{0.2f, 1.6f, 0}, {0.3f, 1.9f, 0.1f}, {30, 180, 30}},
                                  {{-0.6f, 2.2f, 0}, {-0.4f, 2.3f, 0.3f}, {220, 200, 20}}}};
  const float f = 600.0f, cx = (width - 1) / 2.0f, cy = (height - 1) / 2.0f;
  Cloud c;
  c.width = width, c.height = height;
  c.points.resize(std::size_t(width) * height);
  c.colors.resize(c.points.size());
  Rng rng(seed);
  const Eigen::Vector3f none = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
  if (truth) truth->assign(c.points.size(), none);
  for (std::uint32_t v = 0; v < height; ++v)
    for (std::uint32_t u = 0; u < width; ++u) {
      const Eigen::Vector3f ray_c((u - cx) / f, (v - cy) / f, 1.0f);
      const Eigen::Vector3f d = R * ray_c.normalized();
      float t = d.z() < 0 ? -h / d.z() : std::numeric_limits<float>::infinity();
      Rgb8 col{170, 160, 120};  // sand
      Eigen::Vector3f n_level(0, 0, 1);
      for (const Box& b : boxes) {
        int face = 0;
        if (const float tb = hit_box(b, cam, d, face); tb < t) {
          t = tb, col = b.color;
          n_level = Eigen::Vector3f::Zero();
          n_level[face] = d[face] > 0 ? -1.0f : 1.0f;  // the face entered faces the ray
        }
      }
      const std::size_t i = std::size_t(v) * width + u;
      Eigen::Vector3f p = R.transpose() * (t * d);  // back to the optical frame
      if (!std::isfinite(t) || p.norm() > 6.0f) {
        c.points[i] = none;
        continue;
      }
      if (truth) (*truth)[i] = R.transpose() * n_level;
      p *= 1.0f + noise * p.z() * float(rng.normal());  // depth noise along the ray, ~z^2
      c.points[i] = p;
      c.colors[i] = col;
    }
  return c;
}

}  // namespace uwgrasp::bench
