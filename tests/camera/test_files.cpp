// Calibration files: ROS camera_info and uwgrasp's stereo file written and read back, OpenCV's
// FileStorage files (as its own calibration samples write them) read, and bad files named.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>

#include "uwgrasp/camera/files.hpp"
#include "uwgrasp/core/error.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::camera;
namespace fs = std::filesystem;

std::string write(const std::string& name, const std::string& text) {
  const std::string p = (fs::temp_directory_path() / ("uwgrasp_camfile_" + name)).string();
  std::ofstream(p) << text;
  return p;
}

Pinhole lens() {
  Pinhole c;
  c.width = 640, c.height = 480;
  c.fx = 535.4, c.fy = 539.2, c.cx = 320.1, c.cy = 247.6;
  c.distortion = {-0.28, 0.074, 0.0012, -0.0009, 0.012};
  return c;
}

void expect_same(const Pinhole& a, const Pinhole& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_DOUBLE_EQ(a.fx, b.fx);
  EXPECT_DOUBLE_EQ(a.fy, b.fy);
  EXPECT_DOUBLE_EQ(a.cx, b.cx);
  EXPECT_DOUBLE_EQ(a.cy, b.cy);
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(a.distortion[i], b.distortion[i]);
}

TEST(CameraFiles, RosCameraInfoRoundTrips) {
  expect_same(read_camera(write("ros.yaml", camera_yaml(lens()))), lens());
}

TEST(CameraFiles, StereoFileRoundTrips) {
  StereoRig s{lens(), lens(), Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.119, 0.001, 0.002)};
  s.right.fx = 536.0;
  s.R = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const StereoRig back = read_stereo(write("rig.yaml", stereo_yaml(s)));
  expect_same(back.left, s.left);
  expect_same(back.right, s.right);
  EXPECT_LT((back.R - s.R).norm(), 1e-15);
  EXPECT_LT((back.T - s.T).norm(), 1e-15);
}

TEST(CameraFiles, OpenCvFileStorageIsRead) {
  const Pinhole c = lens();
  const cv::Mat K = (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  const cv::Mat D = (cv::Mat_<double>(1, 5) << c.distortion[0], c.distortion[1], c.distortion[2],
                     c.distortion[3], c.distortion[4]);
  for (const char* ext : {".yml", ".xml"}) {
    const std::string mono =
        (fs::temp_directory_path() / (std::string("uwgrasp_cv_mono") + ext)).string();
    {
      cv::FileStorage f(mono, cv::FileStorage::WRITE);
      f << "image_width" << 640 << "image_height" << 480 << "camera_matrix" << K
        << "distortion_coefficients" << D;
    }
    expect_same(read_camera(mono), c);
    const std::string rig =
        (fs::temp_directory_path() / (std::string("uwgrasp_cv_rig") + ext)).string();
    {
      cv::FileStorage f(rig, cv::FileStorage::WRITE);
      const cv::Mat R = cv::Mat::eye(3, 3, CV_64F), T = (cv::Mat_<double>(3, 1) << -0.1, 0, 0);
      f << "imageSize" << std::vector<int>{640, 480} << "M1" << K << "D1" << D << "M2" << K << "D2"
        << D << "R" << R << "T" << T;
    }
    const StereoRig s = read_stereo(rig);
    expect_same(s.right, c);
    EXPECT_NEAR(s.baseline(), 0.1, 1e-15);
  }
}

std::string error_of(const std::string& text, bool stereo = false) {
  const std::string p = write("bad.yaml", text);
  try {
    stereo ? (void)read_stereo(p) : (void)read_camera(p);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CameraFiles, BadFilesNameWhatIsWrong) {
  EXPECT_NE(error_of("image_width: 640\nimage_height: 480\n").find("missing the camera matrix"),
            std::string::npos);
  EXPECT_NE(error_of("image_width: 640\nimage_height: 480\nK: [1, 0, 320, 0, 1, 240, 0, 0]\n")
                .find("K must hold 9"),
            std::string::npos);
  EXPECT_NE(error_of("image_width: 640\nimage_height: 480\nK: [0, 0, 320, 0, 0, 240, 0, 0, 1]\n")
                .find("singular"),
            std::string::npos);
  EXPECT_NE(
      error_of("image_height: 480\nK: [500, 0, 320, 0, 500, 240, 0, 0, 1]\n").find("image_width"),
      std::string::npos);
  EXPECT_NE(error_of("image_width: 640\nimage_height: 480\nK: [a, b]\n").find("not a number"),
            std::string::npos);
  EXPECT_NE(error_of("a: [\n").find("not valid YAML"), std::string::npos);
  EXPECT_NE(
      error_of(
          "image_width: 640\nimage_height: 480\nleft: {K: [500, 0, 320, 0, 500, 240, 0, 0, 1]}\n",
          true)
          .find("missing right"),
      std::string::npos);
  const std::string no_file =
      (fs::temp_directory_path() / "uwgrasp_no_such_calibration.yaml").string();
  EXPECT_THROW(read_camera(no_file), Error);
}

}  // namespace
