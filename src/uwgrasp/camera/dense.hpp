#pragma once
// Dense stereo (thesis 3.6, 3.8): the pair rectified (epipolar lines become image rows),
// semi-global matching (OpenCV's StereoSGBM, Hirschmuller 2008) with its left-right consistency
// check and speckle filter, and the disparity turned into an organised XYZRGB cloud in the left
// camera's optical frame: Z = f B / d (eq. 3.25), NaN where no match or beyond the range limit.
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "uwgrasp/camera/model.hpp"
#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/port.hpp"
#include "uwgrasp/core/timer.hpp"

namespace uwgrasp::camera {

struct DenseConfig {
  double min_range = 0.5;  // m: the nearest depth searched (sets the largest disparity)
  double max_range = 6.0;  // m (thesis 7.4.1): farther points are NaN (sets the smallest disparity)
  std::uint32_t max_disparities = 256;  // cap on the disparities searched, px
  std::uint32_t block_size = 5;         // matched block side, px (odd)
  std::uint32_t uniqueness = 10;        // % the best cost must beat the second best by
  bool left_right_check = true;         // a pixel's match must match it back...
  std::uint32_t lr_max_diff = 1;        // ...to within this many px
  std::uint32_t speckle_window = 100;   // px: disparity blobs smaller than this are removed...
  std::uint32_t speckle_range = 2;      // ...when their disparities stay within this many px
  std::uint32_t downscale = 1;  // match on the pair shrunk this many times (1 or 2: 4x faster,
                                // half the depth resolution); the cloud keeps every pixel
  std::string mode =
      "3way";  // "sgbm" (5 paths), "3way" (OpenCV's faster parallel variant), "hh" (8 paths)
  double port_reference = 2.0;  // m: behind a flat port, the Pinax maps are exact at this distance
  // px: the matcher's sub-pixel disparity error. SGBM's parabola fit locks towards whole pixels
  // (a pair shifted by 20.25 px comes back 20.06, by 20.75 px 21.0): about 0.2 px even on
  // perfect images, and smooth over many pixels, so a cloud's local scatter does not show it.
  double disparity_sigma = 0.2;
};

// Throws Error naming the field (stereo.*) for a value out of range.
void check(const DenseConfig& cfg);

// The rectification of a rig, computed once and used for every pair it takes.
struct Rectification {
  cv::Mat left_map1, left_map2, right_map1,
      right_map2;         // cv::remap's fixed-point maps; empty: identity
  Pinhole camera;         // the rectified left camera (no distortion)
  double baseline = 0.0;  // m
  cv::Matx33d left_from_rect =
      cv::Matx33d::eye();  // rotates rectified-frame points into the left camera's...
  cv::Vec3d left_origin{0.0, 0.0,
                        0.0};  // ...whose origin is here (behind a port: the Pinax centre)
  int min_disparity = 0, num_disparities = 16;
};

// Throws Error when the rig cannot be rectified (cameras not side by side, a disparity range
// that does not fit the image). With a port, the rig's calibration is the in-air one and each
// camera is replaced by its Pinax virtual camera (pinax.hpp) before rectifying; the maps go
// from the rectified image straight to the raw one.
Rectification rectify(const StereoRig& rig, const DenseConfig& cfg,
                      const std::optional<FlatPort>& port = std::nullopt);

struct DenseFrame {
  cv::Mat left_rectified;  // 8-bit, as given (grey or BGR)
  cv::Mat disparity;       // CV_32F, px; NaN where no match
  Cloud cloud;             // organised, left optical frame, colours from the left image
  double depth_error = 0.0;  // m: the depth's sigma at 1 m (depth_error below)
};

// The depth's sigma at 1 m from the matcher's disparity error: Z = f B / d (eq. 3.25) gives
// dZ = Z^2 dd / (f B), so at depth Z it is Z^2 times this. Matched at 1/downscale of the size,
// a disparity step is downscale pixels.
double depth_error(const Rectification& rect, const DenseConfig& cfg);

// Throws Error naming `what` for empty images, images of different sizes or types, or a size
// other than the rig's. With a timer, records the stages rectify, match and cloud.
DenseFrame dense_stereo(const cv::Mat& left, const cv::Mat& right, const Rectification& rect,
                        const DenseConfig& cfg, const std::string& what = "stereo pair",
                        StageTimer* timer = nullptr);

}  // namespace uwgrasp::camera
