// The pinhole + Brown-Conrady model against OpenCV's projectPoints and undistortPoints, and its
// own round trips.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>

#include "uwgrasp/camera/model.hpp"
#include "uwgrasp/core/error.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::camera;

Pinhole lens() {
  Pinhole c;
  c.width = 640, c.height = 480;
  c.fx = 535.4, c.fy = 539.2, c.cx = 320.1, c.cy = 247.6;
  c.distortion = {-0.28, 0.074, 0.0012, -0.0009, 0.012};  // a real wide-ish lens
  return c;
}

TEST(CameraModel, ProjectsAsOpenCvDoes) {
  const Pinhole c = lens();
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> xy(-0.5, 0.5), z(0.3, 4.0);
  std::vector<cv::Point3d> pts;
  for (int i = 0; i < 300; ++i) {
    const double d = z(rng);
    pts.emplace_back(xy(rng) * d, xy(rng) * d, d);
  }
  const cv::Matx33d K(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  const std::vector<double> D(c.distortion.begin(), c.distortion.end());
  std::vector<cv::Point2d> ref;
  cv::projectPoints(pts, cv::Vec3d::all(0), cv::Vec3d::all(0), K, D, ref);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector2d px = c.project({pts[i].x, pts[i].y, pts[i].z});
    EXPECT_NEAR(px.x(), ref[i].x, 1e-9);
    EXPECT_NEAR(px.y(), ref[i].y, 1e-9);
  }
}

TEST(CameraModel, UnprojectInvertsProjectWithDistortion) {
  const Pinhole c = lens();
  for (int v = 0; v < c.height; v += 37)
    for (int u = 0; u < c.width; u += 41) {
      const Eigen::Vector2d px(u, v);
      const Eigen::Vector3d ray = c.unproject(px);
      EXPECT_DOUBLE_EQ(ray.z(), 1.0);
      EXPECT_NEAR((c.project(2.5 * ray) - px).norm(), 0.0, 1e-7) << u << " " << v;
    }
  // OpenCV's undistortPoints agrees on the normalised coordinates.
  const cv::Matx33d K(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  const std::vector<double> D(c.distortion.begin(), c.distortion.end());
  std::vector<cv::Point2d> in{{10, 12}, {600, 400}, {320, 240}}, out;
  cv::undistortPoints(
      in, out, K, D, cv::noArray(), cv::noArray(),
      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-14));
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Eigen::Vector3d r = c.unproject({in[i].x, in[i].y});
    EXPECT_NEAR(r.x(), out[i].x, 1e-6);
    EXPECT_NEAR(r.y(), out[i].y, 1e-6);
  }
}

TEST(CameraModel, ImpossibleCamerasAreRefused) {
  Pinhole c = lens();
  EXPECT_NO_THROW(check(c, "cam"));
  c.fx = 0;
  EXPECT_THROW(check(c, "cam"), Error);
  c = lens(), c.cx = -40;
  EXPECT_THROW(check(c, "cam"), Error);
  c = lens(), c.width = 4;
  EXPECT_THROW(check(c, "cam"), Error);
  c = lens(), c.distortion[0] = NAN;
  EXPECT_THROW(check(c, "cam"), Error);
  StereoRig s{lens(), lens(), Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.12, 0, 0)};
  EXPECT_NO_THROW(check(s, "rig"));
  EXPECT_NEAR(s.baseline(), 0.12, 1e-15);
  s.R(0, 1) = 0.2;
  EXPECT_THROW(check(s, "rig"), Error);
  s.R.setIdentity(), s.T.setZero();
  EXPECT_THROW(check(s, "rig"), Error);
  try {
    c = lens(), c.fy = -1;
    check(c, "cam.yaml");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cam.yaml: K"), std::string::npos) << e.what();
  }
}

}  // namespace
