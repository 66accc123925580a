// Zhang's calibration against known answers: a stereo rig rendered by the simulator (its
// intrinsics and baseline are exact), and the shared real pairs (OpenCV's stereo_calib sample).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "boards.hpp"
#include "uwgrasp/camera/calibrate.hpp"
#include "uwgrasp/core/error.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::camera;
namespace fs = std::filesystem;

TEST(Calibrate, RenderedBoardsGiveTheSimulatedRigBack) {
  const sim::RenderConfig cfg = test::board_render();
  std::vector<View> left, right;
  int i = 0;
  for (const test::BoardPose& b : test::calibration_poses()) {
    auto [l, r] = test::render_board(b, 0.03, cfg, std::to_string(i++));
    left.push_back(std::move(l)), right.push_back(std::move(r));
  }
  const sim::Intrinsics k = test::sensor_intrinsics();
  const StereoCalibration c = calibrate_stereo(left, right, {9, 6, 0.03});
  EXPECT_TRUE(c.rejected.empty()) << c.rejected.front();
  EXPECT_LT(c.rms, 0.3);
  for (const Pinhole& cam : {c.rig.left, c.rig.right})
    std::printf(
        "fx %.3f fy %.3f cx %.3f cy %.3f k1 %.4f (truth %.3f %.3f %.3f %.3f), rms %.3f, baseline "
        "%.5f\n",
        cam.fx, cam.fy, cam.cx, cam.cy, cam.distortion[0], k.fx, k.fy, k.cx, k.cy, c.rms,
        c.rig.baseline());
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
  for (const char* n :
       {"01", "02", "03", "04", "05", "06", "07", "08", "09", "11", "12", "13", "14"}) {
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
