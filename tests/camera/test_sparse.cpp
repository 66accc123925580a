// Sparse stereo: the DLT against exact projections and OpenCV's triangulatePoints; SIFT and Harris
// matches on the simulated thesis scene against its true depth.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <opencv2/calib3d.hpp>
#include <random>

#include "uwgrasp/camera/sparse.hpp"
#include "uwgrasp/camera/triangulate.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/viz/picture.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::camera;

TEST(Triangulate, DltRecoversKnownPointsToOnePartInAMillion) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d K;
  K << 600, 0, 320, 0, 610, 240, 0, 0, 1;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(0.2 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized())
            .toRotationMatrix();
    const Eigen::Vector3d t(-0.1 - 0.3 * std::abs(u(rng)), 0.02 * u(rng), 0.02 * u(rng));
    Projection P1, P2;
    P1 << K, Eigen::Vector3d::Zero();
    P2 << K * R, K * t;
    cv::Mat cp1(3, 4, CV_64F), cp2(3, 4, CV_64F), x1(2, 1, CV_64F), x2(2, 1, CV_64F), X4;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j) cp1.at<double>(i, j) = P1(i, j), cp2.at<double>(i, j) = P2(i, j);
    for (int k = 0; k < 10; ++k) {
      const Eigen::Vector3d X(u(rng), u(rng), 1.0 + 4.0 * std::abs(u(rng)));
      const Eigen::Vector2d a = (P1 * X.homogeneous()).hnormalized(),
                            b = (P2 * X.homogeneous()).hnormalized();
      const Eigen::Vector3d got = triangulate_dlt(P1, P2, a, b);
      EXPECT_LT((got - X).norm() / X.norm(), 1e-6) << got.transpose() << " vs " << X.transpose();
      x1.at<double>(0) = a.x(), x1.at<double>(1) = a.y(), x2.at<double>(0) = b.x(),
      x2.at<double>(1) = b.y();
      cv::triangulatePoints(cp1, cp2, x1, x2, X4);
      const Eigen::Vector3d ref(X4.at<double>(0) / X4.at<double>(3),
                                X4.at<double>(1) / X4.at<double>(3),
                                X4.at<double>(2) / X4.at<double>(3));
      EXPECT_LT((got - ref).norm() / X.norm(), 1e-6);
    }
  }
}

// Median |z - z_true| / z_true of the matches, z_true from the ideal depth image at the left pixel.
double median_depth_error(const std::string& detector, std::size_t& matches) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const sim::World world(scene);
  sim::RenderConfig cfg;
  cfg.water = sim::water_preset("clear");
  const Pose pose = sim::camera_pose(scene, Mount{});
  const sim::StereoFrame s = sim::render_stereo(world, pose, cfg, 3);
  cfg.noise.enabled = false;
  const sim::Frame truth = sim::render_rgbd(world, pose, cfg, 3);
  const auto& k = s.intrinsics;
  StereoRig rig;
  rig.left = {k.width, k.height, k.fx, k.fy, k.cx, k.cy, {}};
  rig.right = rig.left;
  rig.T = Eigen::Vector3d(-s.baseline, 0, 0);
  SparseConfig sc;
  sc.detector = detector;
  const SparseResult r =
      sparse_stereo(viz::rgb_image(s.left, k.width, k.height),
                    viz::rgb_image(s.right, k.width, k.height), Triangulator(rig), sc);
  EXPECT_LE(r.matches.size(), r.epipolar_passed);
  EXPECT_LE(r.epipolar_passed, r.cross_checked);
  EXPECT_LE(r.cross_checked, r.ratio_passed);
  std::vector<double> err;
  for (const auto& m : r.matches) {
    const std::size_t i = std::size_t(std::lround(m.left.y())) * std::size_t(k.width) +
                          std::size_t(std::lround(m.left.x()));
    const float zt = truth.cloud.points[i].z();
    if (std::isfinite(zt)) err.push_back(std::abs(m.point.z() - zt) / zt);
    EXPECT_LE(m.epipolar, sc.epipolar_px);
  }
  matches = r.matches.size();
  std::nth_element(err.begin(), err.begin() + long(err.size() / 2), err.end());
  const double med = err.empty() ? 1.0 : err[err.size() / 2];
  std::printf(
      "%s: %zu keypoints left, %zu ratio, %zu cross-checked, %zu epipolar, %zu triangulated; "
      "median depth "
      "error %.2f %%\n",
      detector.c_str(), r.left_keypoints, r.ratio_passed, r.cross_checked, r.epipolar_passed,
      r.matches.size(), 100 * med);
  return med;
}

TEST(SparseStereo, SiftAndHarrisMatchesLieOnTheTrueSurface) {
  for (const char* d : {"sift", "harris"}) {
    std::size_t n = 0;
    EXPECT_LT(median_depth_error(d, n), 0.02) << d;
    EXPECT_GT(n, 50u) << d;
  }
}

TEST(SparseStereo, BadConfigsAreNamed) {
  StereoRig rig;
  rig.left = {64, 48, 60, 60, 32, 24, {}};
  rig.right = rig.left;
  rig.T = Eigen::Vector3d(-0.1, 0, 0);
  const cv::Mat a(48, 64, CV_8UC1, cv::Scalar(0));
  SparseConfig c;
  c.detector = "orb";
  EXPECT_THROW(sparse_stereo(a, a, Triangulator(rig), c), Error);
  c = {}, c.ratio = 1.5;
  EXPECT_THROW(sparse_stereo(a, a, Triangulator(rig), c), Error);
  EXPECT_THROW(sparse_stereo(a, cv::Mat(24, 32, CV_8UC1), Triangulator(rig), {}), Error);
  EXPECT_TRUE(sparse_stereo(a, a, Triangulator(rig), {})
                  .matches.empty());  // nothing to match in a blank image
}

}  // namespace
