#include "uwgrasp/camera/dense.hpp"

#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "uwgrasp/camera/pinax.hpp"
#include "uwgrasp/camera/triangulate.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::camera {

namespace {
cv::Matx33d K_of(const Pinhole& c) { return {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1}; }
cv::Mat D_of(const Pinhole& c) {
  return cv::Mat(c.distortion.size(), 1, CV_64F, const_cast<double*>(c.distortion.data())).clone();
}

// A rig that is already rectified (the simulator's, or a camera's own rectified output): same
// lens, no distortion, the right camera straight along the left's +x. Matching needs no remap.
bool already_rectified(const StereoRig& rig) {
  const auto same = [](const Pinhole& a, const Pinhole& b) {
    return a.fx == b.fx && a.fy == b.fy && a.cx == b.cx && a.cy == b.cy && a.width == b.width &&
           a.height == b.height;
  };
  return same(rig.left, rig.right) && !rig.left.distorted() && !rig.right.distorted() &&
         (rig.R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-12 && rig.T.x() < 0.0 &&
         std::abs(rig.T.y()) < 1e-12 && std::abs(rig.T.z()) < 1e-12;
}

// stereoRectify (Bouguet's method: both images turned to a common plane, rows aligned) and the
// maps from the rectified images to the given ones, of `map_type` (CV_16SC2 or CV_32FC1).
void rectify_maps(const StereoRig& rig, Rectification& r, int map_type) {
  const cv::Size size(rig.left.width, rig.left.height);
  cv::Matx33d R, R1, R2;
  cv::Matx34d P1, P2;
  cv::Matx44d Q;
  const cv::Vec3d T(rig.T.x(), rig.T.y(), rig.T.z());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R(i, j) = rig.R(i, j);
  cv::stereoRectify(K_of(rig.left), D_of(rig.left), K_of(rig.right), D_of(rig.right), size, R, T,
                    R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0.0);
  cv::initUndistortRectifyMap(K_of(rig.left), D_of(rig.left), R1, P1, size, map_type, r.left_map1,
                              r.left_map2);
  cv::initUndistortRectifyMap(K_of(rig.right), D_of(rig.right), R2, P2, size, map_type,
                              r.right_map1, r.right_map2);
  r.camera = {size.width, size.height, P1(0, 0), P1(1, 1), P1(0, 2), P1(1, 2), {}};
  r.baseline = std::abs(P2(0, 3) / P2(0, 0));
  r.left_from_rect = R1.t();
}

void disparity_range(Rectification& r, const DenseConfig& cfg) {
  const double fB = r.camera.fx * r.baseline;
  r.min_disparity = int(std::floor(fB / cfg.max_range));
  const int largest = int(std::ceil(fB / cfg.min_range));
  r.num_disparities =
      std::min(int(cfg.max_disparities) / 16 * 16, ((largest - r.min_disparity) / 16 + 1) * 16);
  if (r.min_disparity + r.num_disparities >= r.camera.width)
    throw Error("stereo: the disparities for depths " + std::to_string(cfg.min_range) + "-" +
                std::to_string(cfg.max_range) + " m (" + std::to_string(r.min_disparity) + "-" +
                std::to_string(r.min_disparity + r.num_disparities) + " px) do not fit a " +
                std::to_string(r.camera.width) + " px wide image: raise stereo.min_range");
}

cv::Ptr<cv::StereoSGBM> matcher(int min_disparity, int num_disparities, const DenseConfig& cfg) {
  const int mode = cfg.mode == "sgbm" ? cv::StereoSGBM::MODE_SGBM
                   : cfg.mode == "hh" ? cv::StereoSGBM::MODE_HH
                                      : cv::StereoSGBM::MODE_SGBM_3WAY;
  const int block = int(cfg.block_size), area = block * block;  // grey: one channel
  // P1, P2: the smoothness penalties for disparity steps of 1 and more (OpenCV's suggested scale).
  return cv::StereoSGBM::create(min_disparity, num_disparities, block, 8 * area, 32 * area,
                                cfg.left_right_check ? int(cfg.lr_max_diff) : -1, 0,
                                int(cfg.uniqueness), int(cfg.speckle_window),
                                int(cfg.speckle_range), mode);
}

// SGBM's disparities (x16 fixed point) of the grey rectified pair matched at 1/downscale of its
// size; `valid` is the smallest value that is a match.
cv::Mat match(const cv::Mat& gl, const cv::Mat& gr, const Rectification& r, const DenseConfig& cfg,
              int& valid) {
  const int s = int(cfg.downscale);
  cv::Mat ml = gl, mr = gr;
  if (s > 1) {
    cv::resize(gl, ml, cv::Size(gl.cols / s, gl.rows / s), 0, 0, cv::INTER_AREA);
    cv::resize(gr, mr, cv::Size(gr.cols / s, gr.rows / s), 0, 0, cv::INTER_AREA);
  }
  const int min_d = r.min_disparity / s;
  const int num = ((r.min_disparity + r.num_disparities + s - 1) / s - min_d + 15) / 16 * 16;
  // SGBM leaves the first min + num disparity columns unmatched (a band 20-30 % of the image
  // wide); padded on the left, they are matched wherever the right camera sees them too.
  const int pad = min_d + num;
  cv::Mat pl, pr, padded;
  cv::copyMakeBorder(ml, pl, 0, 0, pad, 0, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::copyMakeBorder(mr, pr, 0, 0, pad, 0, cv::BORDER_CONSTANT, cv::Scalar(0));
  matcher(min_d, num, cfg)->compute(pl, pr, padded);
  valid = std::max(1, min_d * 16);
  return padded.colRange(pad, padded.cols);
}
}  // namespace

void check(const DenseConfig& c) {
  const auto fail = [](const std::string& key, const std::string& why) {
    throw Error("stereo." + key + " " + why);
  };
  if (!(c.min_range > 0.0) || !std::isfinite(c.min_range)) fail("min_range", "must be positive");
  if (!(c.max_range > c.min_range) || !std::isfinite(c.max_range))
    fail("max_range", "must exceed min_range");
  if (c.max_disparities < 16 || c.max_disparities > 1024)
    fail("max_disparities", "must be in [16, 1024]");
  if (c.block_size < 1 || c.block_size > 21 || c.block_size % 2 == 0)
    fail("block_size", "must be odd, 1-21");
  if (c.uniqueness > 100) fail("uniqueness", "must be a percentage");
  if (c.downscale < 1 || c.downscale > 4) fail("downscale", "must be 1-4");
  if (c.lr_max_diff > 64) fail("lr_max_diff", "must be <= 64 px");
  if (c.speckle_window > 100000 || c.speckle_range > 64)
    fail("speckle_window", "or speckle_range is absurd");
  if (c.mode != "sgbm" && c.mode != "3way" && c.mode != "hh")
    fail("mode", "must be sgbm, 3way or hh");
  if (!(c.port_reference > 0.0) || !std::isfinite(c.port_reference))
    fail("port_reference", "must be positive");
  if (!(c.disparity_sigma >= 0.0) || c.disparity_sigma > 10.0)
    fail("disparity_sigma", "must be in [0, 10] px");
}

Rectification rectify(const StereoRig& rig, const DenseConfig& cfg,
                      const std::optional<FlatPort>& port) {
  check(rig, "stereo rig");
  check(cfg);
  if (rig.left.width != rig.right.width || rig.left.height != rig.right.height)
    throw Error("stereo rig: the two cameras' image sizes differ");
  const Eigen::Vector3d right_centre = -rig.R.transpose() * rig.T;  // in the left camera's frame
  if (std::abs(right_centre.x()) < std::abs(right_centre.y()))
    throw Error(
        "stereo rig: the right camera is above or below the left one; only side-by-side rigs are "
        "matched");
  if (right_centre.x() < 0.0)
    throw Error(
        "stereo rig: the right camera is on the left camera's left: swap the images (or the "
        "calibration)");
  Rectification r;
  if (!port) {
    if (already_rectified(rig))
      r.camera = rig.left, r.baseline = rig.baseline();
    else
      rectify_maps(rig, r, CV_16SC2);
  } else {
    // Each camera by its Pinax virtual camera: x = x' + c e_z in each, so x_r' = R x_l' + T'.
    const Pinax pl = make_pinax(rig.left, *port, cfg.port_reference);
    const Pinax pr = make_pinax(rig.right, *port, cfg.port_reference);
    rectify_maps(virtual_rig(rig, pl, pr), r, CV_32FC1);
    // Rectified -> virtual (the maps just made) composed with virtual -> raw (Pinax's).
    cv::Mat lx, ly, rx, ry;
    cv::remap(pl.map_x, lx, r.left_map1, r.left_map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT, -1);
    cv::remap(pl.map_y, ly, r.left_map1, r.left_map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT, -1);
    cv::remap(pr.map_x, rx, r.right_map1, r.right_map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT, -1);
    cv::remap(pr.map_y, ry, r.right_map1, r.right_map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT, -1);
    cv::convertMaps(lx, ly, r.left_map1, r.left_map2, CV_16SC2);
    cv::convertMaps(rx, ry, r.right_map1, r.right_map2, CV_16SC2);
    r.left_origin = cv::Vec3d(0.0, 0.0, pl.centre_z);
  }
  disparity_range(r, cfg);
  return r;
}

double depth_error(const Rectification& rect, const DenseConfig& cfg) {
  const double fB = rect.camera.fx * rect.baseline;
  return fB > 0.0 ? cfg.disparity_sigma * double(cfg.downscale) / fB : 0.0;
}

namespace {
// The pair fits the calibration: one size, the calibrated one, 8-bit grey or colour.
void check_pair(const cv::Mat& left, const cv::Mat& right, const Rectification& rect,
                const std::string& what) {
  if (left.empty() || right.empty()) throw Error(what + ": an image is empty");
  if (left.size() != right.size() || left.type() != right.type())
    throw Error(what + ": the images differ in size or type (" + std::to_string(left.cols) + " x " +
                std::to_string(left.rows) + " and " + std::to_string(right.cols) + " x " +
                std::to_string(right.rows) + ")");
  if (left.cols != rect.camera.width || left.rows != rect.camera.height)
    throw Error(what + ": " + std::to_string(left.cols) + " x " + std::to_string(left.rows) +
                " images, but the calibration is for " + std::to_string(rect.camera.width) + " x " +
                std::to_string(rect.camera.height));
  if (left.depth() != CV_8U || (left.channels() != 1 && left.channels() != 3))
    throw Error(what + ": images must be 8-bit grey or colour");
}

// The organised cloud (and the disparity image, NaN where none) of SGBM's fixed-point
// disparities `raw` at the rectified left image's pixels: `valid` is the least valid value.
void triangulate(const cv::Mat& raw, int valid, const Rectification& rect, const DenseConfig& cfg,
                 bool bgr, DenseFrame& out) {
  const Pinhole& k = rect.camera;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const double fB = k.fx * rect.baseline;
  const int W = out.left_rectified.cols, H = out.left_rectified.rows, scale = int(cfg.downscale);
  out.disparity.create(out.left_rectified.size(), CV_32F);
  Cloud& c = out.cloud;
  c.width = std::uint32_t(W), c.height = std::uint32_t(H);
  c.points.resize(std::size_t(W) * std::size_t(H));
  c.colors.resize(c.points.size());
  const cv::Matx33d& M = rect.left_from_rect;
  cv::parallel_for_(cv::Range(0, H), [&](const cv::Range& rows) {
    for (int v = rows.start; v < rows.end; ++v) {
      const auto* d16 = raw.ptr<short>(std::min(v / scale, raw.rows - 1));
      const auto* px = out.left_rectified.ptr<std::uint8_t>(v);
      auto* disp = out.disparity.ptr<float>(v);
      for (int u = 0; u < W; ++u) {
        const std::size_t i = std::size_t(v) * c.width + std::size_t(u);
        c.colors[i] =
            bgr ? Rgb8{px[3 * u + 2], px[3 * u + 1], px[3 * u]} : Rgb8{px[u], px[u], px[u]};
        c.points[i] = Eigen::Vector3f::Constant(nan);
        disp[u] = nan;
        // SGBM's disparities are fixed point with 4 fractional bits, in the matched image's pixels.
        const short q = d16[std::min(u / scale, raw.cols - 1)];
        const double d = q * scale / 16.0;
        if (q < valid) continue;
        const double z = fB / d;  // eq. 3.25
        if (z > cfg.max_range) continue;
        disp[u] = float(d);
        const cv::Vec3d p =
            M * cv::Vec3d((u - k.cx) * z / k.fx, (v - k.cy) * z / k.fy, z) + rect.left_origin;
        c.points[i] = Eigen::Vector3f(float(p[0]), float(p[1]), float(p[2]));
      }
    }
  });
}
}  // namespace

DenseFrame dense_stereo(const cv::Mat& left, const cv::Mat& right, const Rectification& rect,
                        const DenseConfig& cfg, const std::string& what, StageTimer* timer) {
  const auto stage = [&](const char* name) {
    if (timer) timer->start(name);
  };
  check_pair(left, right, rect, what);
  DenseFrame out;
  cv::Mat right_rect;
  stage("rectify");
  if (rect.left_map1.empty()) {
    out.left_rectified = left, right_rect = right;
  } else {
    cv::remap(left, out.left_rectified, rect.left_map1, rect.left_map2, cv::INTER_LINEAR);
    cv::remap(right, right_rect, rect.right_map1, rect.right_map2, cv::INTER_LINEAR);
  }
  // Matched on grey: colour triples the cost for little gain on underwater images.
  cv::Mat gl = out.left_rectified, gr = right_rect, raw;
  if (left.channels() == 3)
    cv::cvtColor(out.left_rectified, gl, cv::COLOR_BGR2GRAY),
        cv::cvtColor(right_rect, gr, cv::COLOR_BGR2GRAY);
  stage("match");
  int valid = 0;
  raw = match(gl, gr, rect, cfg, valid);
  stage("cloud");
  triangulate(raw, valid, rect, cfg, left.channels() == 3, out);
  out.depth_error = depth_error(rect, cfg);
  if (timer) timer->stop();
  return out;
}

}  // namespace uwgrasp::camera
