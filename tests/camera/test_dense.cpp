// Dense stereo against the simulator's truth: the thesis scene rendered as a stereo pair and as
// an ideal depth image from the same pose; a rectification round trip on a distorted, turned rig.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "uwgrasp/camera/dense.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/viz/picture.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::camera;

StereoRig rig_of(const sim::StereoFrame& f) {
  StereoRig r;
  const auto& k = f.intrinsics;
  r.left = {k.width, k.height, k.fx, k.fy, k.cx, k.cy, {}};
  r.right = r.left;
  r.T = Eigen::Vector3d(-f.baseline, 0, 0);
  return r;
}

struct Measured {
  double median_rel = 0.0;    // median |z - z_true| / z_true over pixels with z_true <= 2 m
  double completeness = 0.0;  // share of those pixels with a depth
};

Measured thesis_scene(const std::string& water, const std::optional<FlatPort>& port = std::nullopt,
                      bool pinax = true, std::uint32_t downscale = 1) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const sim::World world(scene);
  sim::RenderConfig cfg;
  cfg.water = sim::water_preset(water);
  cfg.port = port;
  const Pose pose = sim::camera_pose(scene, Mount{});
  const sim::StereoFrame s = sim::render_stereo(world, pose, cfg, 3);
  cfg.noise.enabled = false;  // the truth: an ideal depth image from the left camera
  const sim::Frame truth = sim::render_rgbd(world, pose, cfg, 3);
  const int W = s.intrinsics.width, H = s.intrinsics.height;
  DenseConfig dc;
  dc.downscale = downscale;
  const DenseFrame d = dense_stereo(viz::rgb_image(s.left, W, H), viz::rgb_image(s.right, W, H),
                                    rectify(rig_of(s), dc, pinax ? port : std::nullopt), dc);
  EXPECT_EQ(d.cloud.width, std::uint32_t(W));
  EXPECT_EQ(d.cloud.height, std::uint32_t(H));
  std::vector<double> rel;
  int near = 0;
  for (std::size_t i = 0; i < d.cloud.size(); ++i) {
    const float zt = truth.cloud.points[i].z();
    if (!std::isfinite(zt) || zt > 2.0f) continue;
    ++near;
    const float z = d.cloud.points[i].z();
    if (std::isfinite(z)) rel.push_back(std::abs(double(z) - zt) / zt);
  }
  Measured m;
  m.completeness = double(rel.size()) / std::max(near, 1);
  std::nth_element(rel.begin(), rel.begin() + long(rel.size() / 2), rel.end());
  m.median_rel = rel.empty() ? 1.0 : rel[rel.size() / 2];
  return m;
}

TEST(DenseStereo, ThesisSceneDepthWithinOnePercentInClearWater) {
  const Measured clear = thesis_scene("clear");
  std::printf("clear: median depth error %.3f %%, completeness %.1f %%\n", 100 * clear.median_rel,
              100 * clear.completeness);
  EXPECT_LT(clear.median_rel, 0.01);
  EXPECT_GT(clear.completeness, 0.85);  // the left band SGBM skips is matched too
}

// Matched at half size (the real-time setting): a full-size cloud, the depth still within 1 %.
TEST(DenseStereo, MatchedAtHalfSizeTheDepthStaysWithinOnePercent) {
  const Measured half = thesis_scene("clear", std::nullopt, true, 2);
  std::printf("half size: median depth error %.3f %%, completeness %.1f %%\n",
              100 * half.median_rel, 100 * half.completeness);
  EXPECT_LT(half.median_rel, 0.01);
  EXPECT_GT(half.completeness, 0.85);
}

// Behind a flat port, the air calibration with Pinax keeps the depth as good as in open water;
// without it every depth is about a quarter short (the port magnifies disparities ~n_water).
TEST(DenseStereo, BehindAFlatPortPinaxKeepsTheDepthRight) {
  const FlatPort port{0.02, 0.012, 1.0, 1.49, 1.34};
  const Measured with = thesis_scene("clear", port), without = thesis_scene("clear", port, false);
  std::printf(
      "through the port: median depth error %.3f %% with Pinax (completeness %.1f %%), %.1f %% "
      "without\n",
      100 * with.median_rel, 100 * with.completeness, 100 * without.median_rel);
  EXPECT_LT(with.median_rel, 0.01);
  EXPECT_GT(without.median_rel, 0.15);
  EXPECT_GT(with.completeness, 0.8);
}

// The depth error from the disparity error: eq. 3.25's Z = f B / d moved by a disparity error
// sigma gives f B / (f B / Z - sigma) - Z, to first order Z^2 sigma / (f B).
TEST(DenseStereo, DepthErrorIsTheDisparityErrorThroughEq325) {
  StereoRig rig;
  rig.left = {640, 480, 500, 500, 320, 240, {}};
  rig.right = rig.left;
  rig.T = Eigen::Vector3d(-0.1, 0, 0);
  DenseConfig c;
  const Rectification r = rectify(rig, c);
  const double fB = 500.0 * 0.1;
  EXPECT_NEAR(depth_error(r, c), c.disparity_sigma / fB, 1e-12);
  for (const double z : {0.5, 1.0, 2.0}) {
    const double moved = fB / (fB / z - c.disparity_sigma) - z;
    EXPECT_NEAR(depth_error(r, c) * z * z, moved, 0.01 * moved) << z;
  }
  c.downscale = 2;  // matched at half size: a disparity step is two pixels
  EXPECT_NEAR(depth_error(r, c), 2.0 * c.disparity_sigma / fB, 1e-12);
  c = {}, c.disparity_sigma = 0.0;
  EXPECT_EQ(depth_error(r, c), 0.0);
  c.disparity_sigma = -0.1;
  EXPECT_THROW(rectify(rig, c), Error);
  c.disparity_sigma = 20.0;
  EXPECT_THROW(rectify(rig, c), Error);
}

// The default disparity error is the matcher's own: on the thesis scene's pair, SGBM's
// disparities against the true ones (f B / Z of the ideal depth image), median over the pixels
// nearer than 2 m. The frame carries the depth error it gives.
TEST(DenseStereo, DefaultDisparityErrorIsTheMatchersOwn) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const sim::World world(scene);
  sim::RenderConfig cfg;
  const Pose pose = sim::camera_pose(scene, Mount{});
  const sim::StereoFrame s = sim::render_stereo(world, pose, cfg, 5);
  cfg.noise.enabled = false;
  const sim::Frame truth = sim::render_rgbd(world, pose, cfg, 5);
  const int W = s.intrinsics.width, H = s.intrinsics.height;
  const DenseConfig dc;
  const Rectification r = rectify(rig_of(s), dc);
  const DenseFrame d =
      dense_stereo(viz::rgb_image(s.left, W, H), viz::rgb_image(s.right, W, H), r, dc);
  const double fB = r.camera.fx * r.baseline;
  EXPECT_DOUBLE_EQ(d.depth_error, dc.disparity_sigma / fB);
  std::vector<double> off;
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const float zt = truth.cloud.points[std::size_t(v * W + u)].z();
      const float got = d.disparity.at<float>(v, u);
      if (std::isfinite(zt) && zt <= 2.0f && std::isfinite(got))
        off.push_back(std::abs(got - fB / zt));
    }
  ASSERT_GT(off.size(), 100000u);
  std::nth_element(off.begin(), off.begin() + long(off.size() / 2), off.end());
  const double median = off[off.size() / 2];
  std::printf("SGBM's median disparity error %.3f px (stereo.disparity_sigma %.2f px)\n", median,
              dc.disparity_sigma);
  EXPECT_GT(median, 0.5 * dc.disparity_sigma);
  EXPECT_LT(median, 2.0 * dc.disparity_sigma);
}

TEST(DenseStereo, PointsBeyondTheRangeLimitAreNan) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const sim::World world(scene);
  sim::RenderConfig cfg;
  cfg.water = sim::water_preset("clear");
  const sim::StereoFrame s = sim::render_stereo(world, sim::camera_pose(scene, Mount{}), cfg, 3);
  DenseConfig dc;
  dc.max_range = 1.0;
  const DenseFrame d = dense_stereo(viz::rgb_image(s.left, 640, 480),
                                    viz::rgb_image(s.right, 640, 480), rectify(rig_of(s), dc), dc);
  int finite = 0;
  for (const auto& p : d.cloud.points)
    if (std::isfinite(p.z())) {
      ++finite;
      EXPECT_LE(p.z(), 1.0f + 1e-5f);
    }
  EXPECT_GT(finite, 1000);
  for (int v = 0; v < 480; v += 7)
    for (int u = 0; u < 640; u += 7)
      EXPECT_EQ(std::isfinite(d.disparity.at<float>(v, u)),
                std::isfinite(d.cloud.points[std::size_t(v) * 640 + u].z()));
}

// A turned, distorted rig: rectification maps a known point's two images onto one row, and the
// cloud puts it back where it was in the left camera's frame.
TEST(DenseStereo, RectificationOfATurnedDistortedRig) {
  StereoRig rig;
  rig.left = {640, 480, 520.0, 522.0, 318.0, 243.0, {-0.2, 0.05, 0.001, -0.001, 0.0}};
  rig.right = {640, 480, 515.0, 516.0, 325.0, 238.0, {-0.18, 0.04, 0.0, 0.0, 0.0}};
  rig.R = Eigen::AngleAxisd(0.03, Eigen::Vector3d(0.2, 1, 0.1).normalized()).toRotationMatrix();
  rig.T = Eigen::Vector3d(-0.1, 0.002, 0.001);
  const Rectification r = rectify(rig, {});
  ASSERT_FALSE(r.left_map1.empty());
  EXPECT_NEAR(r.baseline, rig.T.norm(), 1e-9);
  // A point 1.2 m in front: its rectified images share a row, and the disparity gives its depth.
  const Eigen::Vector3d p(0.1, -0.05, 1.2), pr = rig.R * p + rig.T;
  const Eigen::Vector2d a = rig.left.project(p), b = rig.right.project(pr);
  // The maps send rectified pixels to raw ones; find the rectified pixel of each raw image point.
  const auto rectified_of = [](const cv::Mat& m1, const cv::Mat& m2, const Eigen::Vector2d& raw) {
    cv::Mat fx, fy;
    cv::convertMaps(m1, m2, fx, fy, CV_32FC1);
    double best = 1e9;
    Eigen::Vector2d at;
    for (int v = 0; v < fx.rows; ++v)
      for (int u = 0; u < fx.cols; ++u) {
        const double e = std::hypot(fx.at<float>(v, u) - raw.x(), fy.at<float>(v, u) - raw.y());
        if (e < best) best = e, at = Eigen::Vector2d(u, v);
      }
    EXPECT_LT(best, 1.0);
    return at;
  };
  const Eigen::Vector2d ra = rectified_of(r.left_map1, r.left_map2, a),
                        rb = rectified_of(r.right_map1, r.right_map2, b);
  EXPECT_LE(std::abs(ra.y() - rb.y()), 1.0);
  const double z_rect = r.camera.fx * r.baseline / (ra.x() - rb.x());
  const cv::Vec3d q =
      r.left_from_rect * cv::Vec3d((ra.x() - r.camera.cx) * z_rect / r.camera.fx,
                                   (ra.y() - r.camera.cy) * z_rect / r.camera.fy, z_rect);
  EXPECT_LT((Eigen::Vector3d(q[0], q[1], q[2]) - p).norm(), 0.05);  // to the pixel the search found
}

TEST(DenseStereo, BadPairsAndRigsAreNamed) {
  StereoRig rig;
  rig.left = {640, 480, 500, 500, 320, 240, {}};
  rig.right = rig.left;
  rig.T = Eigen::Vector3d(-0.1, 0, 0);
  const Rectification r = rectify(rig, {});
  EXPECT_TRUE(r.left_map1.empty());  // already rectified: no remap
  const cv::Mat a(480, 640, CV_8UC1, cv::Scalar(0)), b(240, 320, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(dense_stereo(a, b, r, {}), Error);
  EXPECT_THROW(dense_stereo(b, b, r, {}), Error);
  EXPECT_THROW(dense_stereo(a, cv::Mat(), r, {}), Error);
  rig.T = Eigen::Vector3d(0.1, 0, 0);  // right camera on the left
  EXPECT_THROW(rectify(rig, {}), Error);
  rig.T = Eigen::Vector3d(0, -0.1, 0);  // one above the other
  EXPECT_THROW(rectify(rig, {}), Error);
  rig.T = Eigen::Vector3d(-0.1, 0, 0);
  DenseConfig c;
  c.min_range = 0.01,
  c.max_disparities = 1024;  // 5000 px of disparity, more than the image is wide
  EXPECT_THROW(rectify(rig, c), Error);
  c = {}, c.block_size = 4;
  EXPECT_THROW(rectify(rig, c), Error);
  c = {}, c.mode = "fast";
  EXPECT_THROW(rectify(rig, c), Error);
}

}  // namespace
