// Zhang's calibration against known answers: a stereo rig rendered by the simulator (its
// intrinsics and baseline are exact), and the shared real pairs (OpenCV's stereo_calib sample).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "uwgrasp/camera/calibrate.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/render.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::camera;
namespace fs = std::filesystem;

// The camera at the origin of W looking along +x (W z up): optical z = W x, x = -W y, y = -W z.
Pose camera_along_x() {
  Pose p = Pose::Identity();
  p.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return p;
}

// The renderer samples each pixel once (hard, aliased edges); a real sensor integrates over the
// pixel. Rendered at three times the size and area-averaged down, the image is what a 640 x 480
// sensor with the third-size intrinsics sees (pixel centres map as u = (U - 1) / 3).
cv::Mat grey_third(const std::vector<Rgb8>& rgb, int w, int h) {
  cv::Mat m(h, w, CV_8UC1), small;
  for (int i = 0; i < w * h; ++i) m.data[i] = rgb[std::size_t(i)].g;
  cv::resize(m, small, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
  return small;
}

// A 9 x 6 board (3 cm squares) at `distance` in front of the camera, turned by `yaw` about W z and
// `pitch` about W y from facing the camera, shifted across the view by (dy, dz).
sim::Scene board_scene(double distance, double yaw, double pitch, double dy, double dz) {
  sim::Scene s;
  s.name = "board";
  s.seafloor.enabled = false;
  Pose p = Pose::Identity();
  p.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();  // the board's z towards the camera (W -x)
  p.translation() = Eigen::Vector3d(distance, dy, dz);
  sim::Shape board{.kind = sim::ShapeKind::box, .size = Eigen::Vector3d(0.36, 0.27, 0.005)};
  board.checker = {9, 6, 0.03};
  s.objects.push_back({"board", {{board, Pose::Identity()}}, p, {255, 255, 255}, true});
  return s;
}

TEST(Calibrate, RenderedBoardsGiveTheSimulatedRigBack) {
  sim::RenderConfig cfg;
  cfg.noise.enabled = false;
  cfg.water.attenuation.setZero();
  cfg.water.veiling.setZero();
  cfg.camera.width = 1920, cfg.camera.height = 1440;
  std::vector<View> left, right;
  // Distance, yaw, pitch, shift: the board near the image's centre and corners, turned up to 35
  // deg each way (Zhang needs the turns to separate the focal length from the distance).
  const double poses[][5] = {{0.75, 0.0, 0.0, 0.0, 0.0},      {0.8, 0.6, 0.0, 0.05, 0.0},    {0.8, -0.6, 0.0, -0.05, 0.0},
                             {0.8, 0.0, 0.6, 0.0, 0.04},      {0.8, 0.0, -0.6, 0.0, -0.04},  {0.9, 0.45, 0.45, 0.15, 0.1},
                             {0.9, -0.45, 0.45, -0.15, 0.1},  {0.9, 0.45, -0.45, 0.15, -0.1}, {0.9, -0.45, -0.45, -0.15, -0.1},
                             {1.1, 0.3, -0.3, 0.25, 0.15},    {1.1, -0.3, 0.3, -0.25, -0.15}, {1.1, 0.3, 0.3, -0.25, 0.15},
                             {1.1, -0.3, -0.3, 0.25, -0.15},  {0.7, 0.3, 0.1, 0.0, 0.0}};
  int i = 0;
  for (const auto& q : poses) {
    const sim::World w(board_scene(q[0], q[1], q[2], q[3], q[4]));
    const sim::StereoFrame f = sim::render_stereo(w, camera_along_x(), cfg, 1);
    const int W = f.intrinsics.width, H = f.intrinsics.height;
    const std::string n = std::to_string(i++);  // (not "L" + n: GCC 12's -Wrestrict false positive)
    left.push_back({n, grey_third(f.left, W, H)});
    right.push_back({n, grey_third(f.right, W, H)});
  }
  sim::CameraConfig sensor = cfg.camera;
  sensor.width = 640, sensor.height = 480;
  const sim::Intrinsics k = sim::make_intrinsics(sensor);
  const StereoCalibration c = calibrate_stereo(left, right, {9, 6, 0.03});
  EXPECT_TRUE(c.rejected.empty()) << c.rejected.front();
  EXPECT_LT(c.rms, 0.3);
  for (const Pinhole& cam : {c.rig.left, c.rig.right})
    std::printf("fx %.3f fy %.3f cx %.3f cy %.3f k1 %.4f (truth %.3f %.3f %.3f %.3f), rms %.3f, baseline %.5f\n", cam.fx,
                cam.fy, cam.cx, cam.cy, cam.distortion[0], k.fx, k.fy, k.cx, k.cy, c.rms, c.rig.baseline());
  for (const Pinhole& cam : {c.rig.left, c.rig.right}) {
    EXPECT_NEAR(cam.fx, k.fx, 0.005 * k.fx);
    EXPECT_NEAR(cam.fy, k.fy, 0.005 * k.fy);
    EXPECT_NEAR(cam.cx, k.cx, 0.005 * k.cx);
    EXPECT_NEAR(cam.cy, k.cy, 0.005 * k.cy);
  }
  EXPECT_NEAR(c.rig.baseline(), cfg.camera.baseline, 0.01 * cfg.camera.baseline);
  EXPECT_LT(c.rig.T.normalized().x(), -0.999);  // the right camera along the left's +x
}

TEST(Calibrate, TooFewBoardsAndMissingBoardsAreNamed) {
  const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(128));
  std::vector<View> views{{"a.png", blank}, {"b.png", blank}, {"c.png", blank}};
  try {
    (void)calibrate(views, {9, 6, 1.0});
    FAIL();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("a.png"), std::string::npos) << m;
    EXPECT_NE(m.find("3"), std::string::npos) << m;
  }
  views.push_back({"small.png", cv::Mat(240, 320, CV_8UC1, cv::Scalar(0))});
  EXPECT_THROW((void)calibrate(views, {9, 6, 1.0}), Error);
  EXPECT_THROW((void)calibrate_stereo(views, {views[0]}, {9, 6, 1.0}), Error);
}

TEST(Calibrate, TheSharedRealPairsCalibrateBelowOnePixel) {
  const fs::path dir = fs::path(UWGRASP_DATA_DIR) / "stereo";
  if (!fs::exists(dir / "left01.jpg")) GTEST_SKIP() << "shared data absent: " << dir;
  std::vector<View> left, right;
  for (const char* n : {"01", "02", "03", "04", "05", "06", "07", "08", "09", "11", "12", "13", "14"}) {
    for (auto* side : {&left, &right}) {
      std::string file = side == &left ? "left" : "right";
      file.append(n).append(".jpg");
      const std::string p = (dir / file).string();
      side->push_back({p, cv::imread(p, cv::IMREAD_GRAYSCALE)});
      ASSERT_FALSE(side->back().image.empty()) << p;
    }
  }
  const StereoCalibration c = calibrate_stereo(left, right, {9, 6, 1.0});
  EXPECT_EQ(c.views.size(), 13u);
  EXPECT_LT(c.rms, 1.0);
  EXPECT_LT(c.left_rms, 1.0);
  EXPECT_LT(c.right_rms, 1.0);
  // The two cameras sit side by side about 3.3 squares apart, the right one along the left's +x.
  EXPECT_NEAR(c.rig.baseline(), 3.34, 0.1);
  EXPECT_LT(c.rig.T.x(), 0.0);
  RecordProperty("stereo_rms_px", std::to_string(c.rms));
}

}  // namespace
