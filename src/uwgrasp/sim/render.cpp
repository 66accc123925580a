// RGB-D and stereo rendering: one ray per pixel centre, shading by the vehicle's lamps at the
// camera (Lambert), the water law of water.hpp, then the depth sensor's noise and dropouts.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/sim/world_impl.hpp"

namespace uwgrasp::sim {

namespace {
constexpr float kFar = 1000.0f;       // rays look this far for colour (beyond the depth limit)
constexpr float kAmbient = 0.25f;     // share of diffuse light not from the lamps

struct Pixel {
  Eigen::Vector3d color = Eigen::Vector3d::Zero();  // 0-1
  float z = 0.0f;                                   // depth, 0 = none
  std::uint16_t label = kLabelWater;
};

std::uint8_t to8(double v) { return static_cast<std::uint8_t>(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5); }

// One pixel's hit: shade by the lamps, apply the water, then decide the depth measurement.
struct Shading {
  const RenderConfig& cfg;
  double cos_grazing;  // cos(noise.grazing_angle), once per frame
};

Pixel shade(const Hit& h, const Eigen::Vector3f& o, const Eigen::Vector3f& d, double ray_norm,
            std::uint64_t pixel, const Shading& sh, std::uint64_t seed) {
  const RenderConfig& cfg = sh.cfg;
  Pixel px;
  if (!h.hit) {
    px.color = cfg.water.veiling;  // open water: veiling light only
    return px;
  }
  const double range = h.t * ray_norm;
  const float cos_i = std::abs(h.normal.dot(d)) / d.norm();
  const Eigen::Vector3f p = o + h.t * d;
  const Eigen::Vector3f albedo = h.surface.checker.square > 0.0 ? checker_albedo(h.surface, p) : h.surface.albedo;
  const Eigen::Vector3d J =
      (albedo * texture_factor(p, h.normal, h.surface.texture) * (kAmbient + (1 - kAmbient) * cos_i)).cast<double>();
  // exp(-c d) in float: the image is 8-bit, the depth does not depend on it.
  const Eigen::Array3d t =
      (-(cfg.water.attenuation.cast<float>().array() * static_cast<float>(range))).exp().cast<double>();
  px.color = underwater_color(J, t, cfg.water);
  px.label = h.surface.label;
  if (h.t < cfg.camera.min_range || h.t > cfg.camera.max_range) return px;
  px.z = h.t;
  if (!cfg.noise.enabled) return px;
  Rng rng(seed, pixel);
  // Dropout probability rises linearly in cos(incidence) from the grazing angle to 90 degrees.
  const double cos_g = sh.cos_grazing;
  const double p_drop = cos_i < cos_g ? (cos_g - cos_i) / cos_g : 0.0;
  const double signal = (J.array() * t).mean();
  if (rng.uniform() < p_drop || signal < cfg.noise.dark_threshold) {
    px.z = 0.0f;
    return px;
  }
  px.z = std::max(0.0f, static_cast<float>(h.t + depth_sigma(h.t, cfg.noise) * rng.normal()));
  return px;
}

// A pixel's primary ray in C: from the camera centre, or, behind a flat port, from the glass's
// outer face in its refracted direction (z = 1 either way, so t along it is the depth gained).
struct PrimaryRay {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(), direction = Eigen::Vector3d::UnitZ();
  bool valid = true;  // false: totally reflected inside the port
};
PrimaryRay primary_ray(const Intrinsics& k, const std::optional<FlatPort>& port, int u, int v) {
  const Eigen::Vector3d ray = k.ray(u, v);
  if (!port) return {Eigen::Vector3d::Zero(), ray, true};
  const auto out = refract_through_port(*port, ray);
  if (!out) return {Eigen::Vector3d::Zero(), ray, false};
  return {out->origin, out->direction, true};
}

// Traces and shades row v of the image seen from camera pose `wc`; `out(u, i, pixel, ray)`.
template <class Out>
void render_row(const World& world, const SnowScene& snow, const Pose& wc, const Intrinsics& k,
                int v, const RenderConfig& cfg, std::uint64_t seed, Out out) {
  const Eigen::Matrix3f R = wc.linear().cast<float>();
  std::vector<PrimaryRay> rays(k.width);
  std::vector<Eigen::Vector3f> origins(cfg.port ? k.width : 1, wc.translation().cast<float>());
  std::vector<Eigen::Vector3f> dirs(k.width);
  std::vector<Hit> hits(k.width);
  for (int u = 0; u < k.width; ++u) {
    rays[u] = primary_ray(k, cfg.port, u, v);
    dirs[u] = R * rays[u].direction.cast<float>();
    if (cfg.port) origins[u] = (wc * rays[u].origin).cast<float>();
  }
  trace(world, snow, origins, dirs, kFar, hits);
  const Shading sh{cfg, std::cos(cfg.noise.grazing_angle)};
  for (int u = 0; u < k.width; ++u) {
    const std::uint64_t i = static_cast<std::uint64_t>(v) * k.width + u;
    if (!rays[u].valid) hits[u] = Hit{};  // no light reaches this pixel through the port
    const Eigen::Vector3f& o = origins[origins.size() == 1 ? 0 : std::size_t(u)];
    out(u, i, shade(hits[u], o, dirs[u], rays[u].direction.norm(), i, sh, seed), rays[u]);
  }
}

void check(const RenderConfig& cfg, const Pose& wc) {
  check_camera(cfg.camera);
  if (cfg.port) check_port(*cfg.port);
  check_water(cfg.water);
  check_noise(cfg.noise);
  if (!wc.matrix().allFinite()) throw Error("sim: camera pose is not finite");
}

template <class F>
void for_rows(int height, F f) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& r) {
    for (int v = r.begin(); v < r.end(); ++v) f(v);
  });
}
}  // namespace

Pose camera_pose(const Scene& scene, const Mount& mount) {
  return world_from_body(scene.vehicle) * body_from_camera(scene.camera_mount.value_or(mount));
}

Frame render_rgbd(const World& world, const Pose& wc, const RenderConfig& cfg, std::uint64_t seed) {
  check(cfg, wc);
  Frame f;
  f.intrinsics = make_intrinsics(cfg.camera);
  f.world_from_camera = wc;
  const Intrinsics& k = f.intrinsics;
  const std::size_t n = static_cast<std::size_t>(k.width) * k.height;
  SnowScene snow;
  make_snow(world, wc, k, cfg, seed, snow);
  f.rgb.resize(n);
  f.depth.resize(n);
  f.labels.resize(n);
  f.cloud.points.resize(n);
  f.cloud.width = static_cast<std::uint32_t>(k.width);
  f.cloud.height = static_cast<std::uint32_t>(k.height);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for_rows(k.height, [&](int v) {
    render_row(world, snow, wc, k, v, cfg, seed, [&](int, std::uint64_t i, const Pixel& px, const PrimaryRay& ray) {
      f.rgb[i] = {to8(px.color.x()), to8(px.color.y()), to8(px.color.z())};
      f.labels[i] = px.label;
      // The measured point along the pixel's ray (through the port, if any): its z is the depth.
      const Eigen::Vector3d p = ray.origin + double(px.z) * ray.direction;
      const double mm = px.z > 0 ? std::round(p.z() * 1000.0) : 0.0;
      f.depth[i] = static_cast<std::uint16_t>(std::min(mm, 65535.0));
      f.cloud.points[i] = px.z > 0 ? p.cast<float>() : Eigen::Vector3f(nan, nan, nan);
    });
  });
  f.cloud.colors = f.rgb;
  return f;
}

StereoFrame render_stereo(const World& world, const Pose& wl, const RenderConfig& cfg,
                          std::uint64_t seed) {
  check(cfg, wl);
  StereoFrame s;
  s.intrinsics = make_intrinsics(cfg.camera);
  s.baseline = cfg.camera.baseline;
  s.world_from_left = wl;
  Pose wr = wl;
  wr.translation() += wl.linear().col(0) * s.baseline;
  const Intrinsics& k = s.intrinsics;
  SnowScene snow;  // one set of particles in the water, seen by both cameras
  make_snow(world, wl, k, cfg, seed, snow);
  const std::size_t n = static_cast<std::size_t>(k.width) * k.height;
  s.left.resize(n);
  s.right.resize(n);
  for (int side = 0; side < 2; ++side) {
    auto& img = side ? s.right : s.left;
    const Pose& pose = side ? wr : wl;
    for_rows(k.height, [&](int v) {
      render_row(world, snow, pose, k, v, cfg, seed, [&](int, std::uint64_t i, const Pixel& px, const PrimaryRay&) {
        img[i] = {to8(px.color.x()), to8(px.color.y()), to8(px.color.z())};
      });
    });
  }
  return s;
}

}  // namespace uwgrasp::sim
