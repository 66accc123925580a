// RGB-D to cloud: the simulator's depth image gives back its own cloud; a distorted camera puts
// each pixel's point on the ray the model says; bad frames are named.
#include <gtest/gtest.h>

#include <cmath>

#include "uwgrasp/camera/rgbd.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/viz/picture.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::camera;

TEST(Rgbd, TheSimulatorsDepthImageGivesItsCloudBack) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const sim::World world(scene);
  sim::RenderConfig cfg;
  cfg.noise.enabled = false;
  const sim::Frame f = sim::render_rgbd(world, sim::camera_pose(scene, Mount{}), cfg, 1);
  const auto& k = f.intrinsics;
  cv::Mat depth(k.height, k.width, CV_16UC1, const_cast<std::uint16_t*>(f.depth.data()));
  const cv::Mat colour = viz::rgb_image(f.rgb, k.width, k.height);
  const Cloud c = rgbd_cloud(depth, colour, {k.width, k.height, k.fx, k.fy, k.cx, k.cy, {}});
  ASSERT_EQ(c.size(), f.cloud.size());
  EXPECT_EQ(c.width, std::uint32_t(k.width));
  EXPECT_EQ(c.height, std::uint32_t(k.height));
  int compared = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(c.colors[i], f.rgb[i]);
    if (f.depth[i] == 0) {
      EXPECT_FALSE(std::isfinite(c.points[i].z()));
      continue;
    }
    // The depth image holds whole millimetres: within half of one, scaled along the ray.
    const Eigen::Vector3f t = f.cloud.points[i];
    EXPECT_NEAR(c.points[i].z(), t.z(), 5.1e-4f);
    EXPECT_NEAR(c.points[i].x(), t.x(), 5.1e-4f * std::max(1.0f, std::abs(t.x() / t.z())));
    ++compared;
  }
  EXPECT_GT(compared, 200000);
}

TEST(Rgbd, ADistortedCameraPutsEachPointOnItsPixelsRay) {
  const Pinhole cam{64, 48, 60.0, 61.0, 31.0, 24.5, {-0.25, 0.06, 0.001, -0.002, 0.0}};
  cv::Mat depth(48, 64, CV_32FC1, cv::Scalar(1.5f));
  depth.at<float>(3, 4) = NAN, depth.at<float>(5, 6) = 0.0f, depth.at<float>(7, 8) = INFINITY;
  const Cloud c = rgbd_cloud(depth, cv::Mat(), cam);
  EXPECT_TRUE(c.colors.empty());
  EXPECT_FALSE(std::isfinite(c.points[3 * 64 + 4].z()));
  EXPECT_FALSE(std::isfinite(c.points[5 * 64 + 6].z()));
  EXPECT_FALSE(std::isfinite(c.points[7 * 64 + 8].z()));
  for (int v = 0; v < 48; v += 5)
    for (int u = 0; u < 64; u += 5) {
      const Eigen::Vector3f p = c.points[std::size_t(v) * 64 + u];
      if (!std::isfinite(p.z())) continue;
      EXPECT_FLOAT_EQ(p.z(), 1.5f);
      EXPECT_LT((cam.project(p.cast<double>()) - Eigen::Vector2d(u, v)).norm(), 1e-4);
    }
}

TEST(Rgbd, BadFramesAreNamed) {
  const Pinhole cam{64, 48, 60.0, 60.0, 32.0, 24.0, {}};
  EXPECT_THROW(rgbd_cloud(cv::Mat(), cv::Mat(), cam), Error);
  EXPECT_THROW(rgbd_cloud(cv::Mat(48, 64, CV_8UC1), cv::Mat(), cam), Error);  // 8-bit depth
  EXPECT_THROW(rgbd_cloud(cv::Mat(40, 64, CV_16UC1), cv::Mat(), cam),
               Error);  // not the camera's size
  EXPECT_THROW(rgbd_cloud(cv::Mat(48, 64, CV_16UC1), cv::Mat(40, 64, CV_8UC3), cam),
               Error);  // not registered
  Pinhole singular = cam;
  singular.fx = 0.0;
  EXPECT_THROW(rgbd_cloud(cv::Mat(48, 64, CV_16UC1), cv::Mat(), singular), Error);
}

}  // namespace
