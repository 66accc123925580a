// The ray-cast RGB-D camera against analytic geometry, the water law and the noise model.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

#include "uwgrasp/cloud/normals.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/render.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::sim;

// A camera at the origin of W looking along +x (W z up): optical z = W x, x = -W y, y = -W z.
Pose camera_looking_along_x(double height = 0.0) {
  Pose p = Pose::Identity();
  p.linear() << 0, 0, 1,  //
      -1, 0, 0,           //
      0, -1, 0;
  p.translation() = Eigen::Vector3d(0, 0, height);
  return p;
}

Scene wall_scene(double distance, Rgb8 color = {200, 200, 200}) {
  Scene s;
  s.name = "wall";
  s.seafloor.enabled = false;
  Pose p = Pose::Identity();
  p.translation() = Eigen::Vector3d(distance + 0.05, 0, 0);  // its near face at `distance`
  s.objects.push_back({"wall", {{Shape{.size = Eigen::Vector3d(0.1, 20, 20)}, Pose::Identity()}}, p, color, true});
  return s;
}

RenderConfig perfect() {
  RenderConfig c;
  c.noise.enabled = false;
  c.water.attenuation.setZero();
  c.water.veiling.setZero();
  return c;
}

TEST(Render, PlaneAtKnownDistanceHasThatDepthAndNormalEverywhere) {
  const World world(wall_scene(1.5));
  const Frame f = render_rgbd(world, camera_looking_along_x(), perfect(), 1);
  ASSERT_EQ(f.cloud.size(), 640u * 480u);
  for (std::size_t i = 0; i < f.cloud.size(); ++i) {
    ASSERT_NEAR(f.cloud.points[i].z(), 1.5f, 1e-4f) << i;
    ASSERT_EQ(f.depth[i], 1500) << i;
    ASSERT_EQ(f.labels[i], kLabelFirstObject);
  }
  Cloud c = f.cloud;
  cloud::compute_normals(c, {});
  for (std::size_t i = 0; i < c.size(); i += 997)
    EXPECT_GT(std::abs(c.normals[i].z()), 0.9999f) << i;  // facing the camera
}

TEST(Render, BoxFacesLandWhereTheGeometrySays) {
  Scene s = wall_scene(1.0);
  s.objects[0].parts[0].shape.size = Eigen::Vector3d(0.2, 0.3, 0.1);
  s.objects[0].pose.translation() = Eigen::Vector3d(1.1, 0.05, -0.02);  // near face at x = 1.0
  const World world(s);
  const Pose wc = camera_looking_along_x(0.3);  // above it: the top face shows too
  const Frame f = render_rgbd(world, wc, perfect(), 1);
  std::size_t front = 0, top = 0;
  for (std::size_t i = 0; i < f.cloud.size(); ++i) {
    if (f.labels[i] != kLabelFirstObject) continue;
    const Eigen::Vector3d w = wc * f.cloud.points[i].cast<double>();
    ASSERT_GE(w.x(), 1.0 - 1e-4);
    ASSERT_LE(w.x(), 1.2 + 1e-4);
    ASSERT_LE(std::abs(w.y() - 0.05), 0.15 + 1e-4);
    ASSERT_LE(std::abs(w.z() + 0.02), 0.05 + 1e-4);
    front += std::abs(w.x() - 1.0) < 1e-4;
    top += std::abs(w.z() - 0.03) < 1e-4;
  }
  EXPECT_GT(front, 1000u);
  EXPECT_GT(top, 100u);
}

TEST(Render, ProjectingTheCloudGivesBackItsPixels) {
  const Scene s = builtin_scene("thesis");
  const World world(s);
  const Frame f = render_rgbd(world, camera_pose(s, Mount{}), perfect(), 1);
  std::size_t checked = 0;
  for (int v = 0; v < 480; v += 7)
    for (int u = 0; u < 640; u += 7) {
      const Eigen::Vector3f& p = f.cloud.points[std::size_t(v) * 640 + u];
      if (!p.allFinite()) continue;
      const Eigen::Vector2d px = f.intrinsics.project(p.cast<double>());
      ASSERT_NEAR(px.x(), u, 1e-3);
      ASSERT_NEAR(px.y(), v, 1e-3);
      ++checked;
    }
  EXPECT_GT(checked, 5000u);
}

TEST(Render, NothingBeyondTheRangeLimit) {
  const World near(wall_scene(5.9)), far(wall_scene(6.1));
  const Frame a = render_rgbd(near, camera_looking_along_x(), perfect(), 1);
  const Frame b = render_rgbd(far, camera_looking_along_x(), perfect(), 1);
  EXPECT_EQ(a.depth[240 * 640 + 320], 5900);
  for (std::size_t i = 0; i < b.depth.size(); ++i) ASSERT_EQ(b.depth[i], 0) << i;
  EXPECT_FALSE(b.cloud.points[0].allFinite());
  EXPECT_EQ(b.labels[0], kLabelFirstObject);  // still seen in colour
}

TEST(Render, DepthNoiseMatchesItsSigma) {
  for (const double d : {1.0, 3.0}) {
    const World world(wall_scene(d));
    RenderConfig c = perfect();
    c.noise.enabled = true;
    c.noise.dark_threshold = 0;
    c.water.snow_density = 0;
    const Frame f = render_rgbd(world, camera_looking_along_x(), c, 7);
    double sum = 0, sum2 = 0;
    std::size_t n = 0;
    for (const auto& p : f.cloud.points) {
      if (!p.allFinite()) continue;
      const double e = p.z() - d;
      sum += e, sum2 += e * e, ++n;
    }
    const double mean = sum / double(n), sigma = std::sqrt(sum2 / double(n) - mean * mean);
    EXPECT_NEAR(sigma, depth_sigma(d, c.noise), 0.1 * depth_sigma(d, c.noise)) << d;
    EXPECT_LT(std::abs(mean), 0.1 * depth_sigma(d, c.noise)) << d;
  }
}

TEST(Render, AttenuationFollowsItsLaw) {
  RenderConfig c = perfect();
  c.water = water_preset("coastal");
  c.noise.enabled = false;
  for (const double d : {0.5, 1.0, 2.0, 4.0}) {
    const World world(wall_scene(d, {160, 160, 160}));
    const std::size_t centre = 240 * 640 + 320;
    const Frame f = render_rgbd(world, camera_looking_along_x(), c, 1);
    const Frame dry = render_rgbd(world, camera_looking_along_x(), perfect(), 1);
    const Rgb8 px = f.rgb[centre], j = dry.rgb[centre];  // j: the surface's own radiance J
    const double range = f.cloud.points[centre].norm();
    const Eigen::Vector3d expect =
        underwater_color(Eigen::Vector3d(j.r, j.g, j.b) / 255.0, range, c.water) * 255.0;
    EXPECT_NEAR(px.r, expect.x(), 1.0) << d;
    EXPECT_NEAR(px.g, expect.y(), 1.0) << d;
    EXPECT_NEAR(px.b, expect.z(), 1.0) << d;
  }
  EXPECT_TRUE(underwater_color(Eigen::Vector3d(0.3, 0.6, 0.9), 0.0, c.water).isApprox(Eigen::Vector3d(0.3, 0.6, 0.9)));
  EXPECT_TRUE(underwater_color(Eigen::Vector3d(0.3, 0.6, 0.9), 1e3, c.water).isApprox(c.water.veiling));
}

TEST(Render, SameSeedSameFrameAtAnyThreadCount) {
  const Scene s = builtin_scene("several");
  const World world(s);
  RenderConfig c;
  c.water = water_preset("turbid");
  const Pose wc = camera_pose(s, Mount{});
  const Frame a = render_rgbd(world, wc, c, 42);
  Frame b;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    b = render_rgbd(world, wc, c, 42);
  }
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_EQ(a.labels, b.labels);
  const Frame other = render_rgbd(world, wc, c, 43);
  EXPECT_NE(a.depth, other.depth);
  std::size_t snow = 0;
  for (const auto l : a.labels) snow += l == kLabelSnow;
  EXPECT_GT(snow, 0u);  // turbid water has particles in view
}

TEST(Render, ImpossibleSettingsAreErrors) {
  const World world(wall_scene(1.0));
  RenderConfig c;
  c.water.veiling.x() = 1.5;
  EXPECT_THROW(render_rgbd(world, camera_looking_along_x(), c, 1), Error);
  c = RenderConfig{};
  c.water.attenuation.y() = -0.1;
  EXPECT_THROW(render_rgbd(world, camera_looking_along_x(), c, 1), Error);
  c = RenderConfig{};
  c.camera.min_range = 7.0;
  EXPECT_THROW(render_rgbd(world, camera_looking_along_x(), c, 1), Error);
  EXPECT_THROW(water_preset("muddy"), Error);
  EXPECT_THROW(builtin_scene("atlantis"), Error);
}

TEST(Render, StereoPairIsTheLeftViewShiftedByTheBaseline) {
  // A textured wall at Z: the right image is the left shifted by f b / Z pixels (55 here).
  const RenderConfig c = perfect();
  const double z = make_intrinsics(c.camera).fx * c.camera.baseline / 55.0;
  const World world(wall_scene(z));
  const StereoFrame s = render_stereo(world, camera_looking_along_x(), c, 1);
  // Block matching along the row must find 55: zero-mean normalised cross-correlation of a
  // 31 x 7 patch (the lamps light the two views slightly differently, so compare shapes).
  const auto zncc = [&](int u, int v, int d) {
    double sl = 0, sr = 0, sll = 0, srr = 0, slr = 0, n = 0;
    for (int dv = -3; dv <= 3; ++dv)
      for (int du = -15; du <= 15; ++du) {
        const double l = s.left[std::size_t(v + dv) * 640 + u + du].g;
        const double r = s.right[std::size_t(v + dv) * 640 + u + du - d].g;
        sl += l, sr += r, sll += l * l, srr += r * r, slr += l * r, n += 1;
      }
    const double cov = slr - sl * sr / n, vl = sll - sl * sl / n, vr = srr - sr * sr / n;
    return cov / std::sqrt(vl * vr + 1e-9);
  };
  int right = 0, total = 0;
  for (int v = 100; v < 380; v += 20)
    for (int u = 120; u < 500; u += 20) {
      int best = 45;
      for (int d = 46; d <= 65; ++d)
        if (zncc(u, v, d) > zncc(u, v, best)) best = d;
      right += best == 55, ++total;
    }
  EXPECT_GT(right, total * 9 / 10);
}

}  // namespace

namespace {
// A small ball off the optical axis, seen through a flat port: its image centre lies where the
// port's inverse (the in-air ray that sees its centre) projects, farther from the image centre
// than in open water (the port narrows the field of view, about by n_water).
TEST(Render, ThroughAFlatPortTheImageIsWhereSnellSendsIt) {
  Scene s;
  s.name = "ball";
  s.seafloor.enabled = false;
  // Camera looking along W +x: C = (-W y, -W z, W x).
  const Eigen::Vector3d centre_c(0.25, -0.15, 1.2);
  Pose p = Pose::Identity();
  p.translation() = Eigen::Vector3d(centre_c.z(), -centre_c.x(), -centre_c.y());
  s.objects.push_back({"ball", {{Shape{.kind = ShapeKind::sphere, .radius = 0.02}, Pose::Identity()}}, p,
                       {200, 200, 200}, true});
  const World w(s);
  RenderConfig cfg = perfect();
  const auto centre_pixel = [&](const RenderConfig& c) {
    const Frame f = render_rgbd(w, camera_looking_along_x(), c, 1);
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    int n = 0;
    for (int v = 0; v < f.intrinsics.height; ++v)
      for (int u = 0; u < f.intrinsics.width; ++u)
        if (f.labels[std::size_t(v) * f.intrinsics.width + u] == kLabelFirstObject) sum += Eigen::Vector2d(u, v), ++n;
    EXPECT_GT(n, 20);
    return std::make_pair(Eigen::Vector2d(sum / n), f);
  };
  const auto [open, f0] = centre_pixel(cfg);
  const Intrinsics k = f0.intrinsics;
  EXPECT_LT((open - k.project(centre_c)).norm(), 0.5);
  cfg.port = FlatPort{0.02, 0.012, 1.0, 1.49, 1.34};
  const auto [ported, f1] = centre_pixel(cfg);
  const Eigen::Vector3d d = *direction_to(*cfg.port, centre_c);
  EXPECT_LT((ported - k.project(d)).norm(), 0.5) << ported.transpose() << " vs " << k.project(d).transpose();
  // Refraction bends the ray towards the axis in water: the ball appears farther out.
  const Eigen::Vector2d c(k.cx, k.cy);
  EXPECT_GT((ported - c).norm(), 1.2 * (open - c).norm());
  // The RGB-D cloud stays the true surface: the ball's points lie on it.
  for (std::size_t i = 0; i < f1.labels.size(); ++i) {
    if (f1.labels[i] != kLabelFirstObject || !std::isfinite(f1.cloud.points[i].x())) continue;
    EXPECT_NEAR((f1.cloud.points[i].cast<double>() - centre_c).norm(), 0.02, 2e-4);
  }
}
}  // namespace
