#pragma once
// Zhang's calibration from views of a checkerboard (thesis 3.1; OpenCV's calibrateCamera and
// stereoCalibrate): inner corners found and refined to sub-pixel, the pinhole + Brown-Conrady
// model fitted by minimising the reprojection error, per-view and overall RMS reported. Views
// where the board is not found are named and left out; fewer than 3 usable views is an error.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "uwgrasp/camera/model.hpp"

namespace uwgrasp::camera {

struct Board {
  int cols = 9, rows = 6;  // inner corners
  double square = 1.0;     // side of a square, in the unit the extrinsics are wanted in (m)
};

// An image and the name to report it by.
struct View {
  std::string name;
  cv::Mat image;  // 8-bit, grey or BGR
};

struct ViewError {
  std::string name;
  double rms = 0.0;  // px; for a stereo pair over both images
};

struct MonoCalibration {
  Pinhole camera;
  double rms = 0.0;                   // px, over every corner of every used view
  std::vector<ViewError> views;       // the used views
  std::vector<std::string> rejected;  // board not found
};

struct StereoCalibration {
  StereoRig rig;
  double rms = 0.0;
  std::vector<ViewError> views;            // the used pairs (named by the left image)
  std::vector<std::string> rejected;       // pairs where either image misses the board
  double left_rms = 0.0, right_rms = 0.0;  // each camera's own calibration
};

// The board's inner corners in an image, refined to sub-pixel; empty when it is not found.
std::vector<cv::Point2f> find_corners(const cv::Mat& image, const Board& board);

// Throws Error naming the problem: images of different sizes, an empty image, fewer than 3
// views where the board is found (naming the ones where it is not), a board smaller than 2 x 2.
MonoCalibration calibrate(const std::vector<View>& views, const Board& board);
StereoCalibration calibrate_stereo(const std::vector<View>& left, const std::vector<View>& right,
                                   const Board& board);

}  // namespace uwgrasp::camera
