#include "uwgrasp/camera/calibrate.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::camera {

namespace {
std::vector<cv::Point3f> board_points(const Board& b) {
  std::vector<cv::Point3f> out;
  for (int r = 0; r < b.rows; ++r)
    for (int c = 0; c < b.cols; ++c)
      out.emplace_back(float(c * b.square), float(r * b.square), 0.0f);
  return out;
}

void check_board(const Board& b) {
  if (b.cols < 2 || b.rows < 2) throw Error("board: needs at least 2 x 2 inner corners");
  if (!(b.square > 0.0) || !std::isfinite(b.square))
    throw Error("board: the square size must be positive");
}

cv::Size same_size(const std::vector<View>& views) {
  cv::Size size;
  for (const View& v : views) {
    if (v.image.empty()) throw Error(v.name + ": empty or unreadable image");
    if (size.area() == 0) size = v.image.size();
    if (v.image.size() != size)
      throw Error(v.name + ": " + std::to_string(v.image.cols) + " x " +
                  std::to_string(v.image.rows) + ", but the other images are " +
                  std::to_string(size.width) + " x " + std::to_string(size.height));
  }
  return size;
}

Pinhole from_cv(const cv::Mat& K, const cv::Mat& D, cv::Size size) {
  Pinhole c;
  c.width = size.width, c.height = size.height;
  c.fx = K.at<double>(0, 0), c.fy = K.at<double>(1, 1), c.cx = K.at<double>(0, 2),
  c.cy = K.at<double>(1, 2);
  for (int i = 0; i < 5 && i < int(D.total()); ++i) c.distortion[std::size_t(i)] = D.at<double>(i);
  return c;
}

// RMS of the reprojection of one view's corners, px.
double view_rms(const std::vector<cv::Point3f>& object, const std::vector<cv::Point2f>& corners,
                const cv::Mat& rvec, const cv::Mat& tvec, const cv::Mat& K, const cv::Mat& D,
                double& sum2) {
  std::vector<cv::Point2f> projected;
  cv::projectPoints(object, rvec, tvec, K, D, projected);
  double s = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const cv::Point2f d = projected[i] - corners[i];
    s += double(d.x) * d.x + double(d.y) * d.y;
  }
  sum2 += s;
  return std::sqrt(s / double(corners.size()));
}

std::string names(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& n : v) out += (out.empty() ? "" : ", ") + n;
  return out;
}

void enough(std::size_t used, const std::vector<std::string>& rejected) {
  if (used >= 3) return;
  throw Error("calibration needs the board in at least 3 views, found it in " +
              std::to_string(used) +
              (rejected.empty() ? std::string() : "; not found in: " + names(rejected)));
}
}  // namespace

std::vector<cv::Point2f> find_corners(const cv::Mat& image, const Board& board) {
  cv::Mat grey;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else
    grey = image;
  std::vector<cv::Point2f> corners;
  const cv::Size pattern(board.cols, board.rows);
  if (!cv::findChessboardCorners(grey, pattern, corners,
                                 cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
    return {};
  // The refinement window (half-side) stays under half the closest corner spacing: a larger one
  // reaches the neighbouring corner on a small or steeply seen board and pulls towards it.
  double spacing = 1e9;
  for (int r = 0; r < board.rows; ++r)
    for (int c = 0; c < board.cols; ++c) {
      const cv::Point2f p = corners[std::size_t(r * board.cols + c)];
      if (c + 1 < board.cols)
        spacing =
            std::min(spacing, double(cv::norm(corners[std::size_t(r * board.cols + c + 1)] - p)));
      if (r + 1 < board.rows)
        spacing =
            std::min(spacing, double(cv::norm(corners[std::size_t((r + 1) * board.cols + c)] - p)));
    }
  const int half = std::clamp(int(0.4 * spacing), 2, 11);
  cv::cornerSubPix(grey, corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 100, 1e-4));
  return corners;
}

MonoCalibration calibrate(const std::vector<View>& views, const Board& board) {
  check_board(board);
  const cv::Size size = same_size(views);
  MonoCalibration out;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<std::string> used;
  for (const View& v : views) {
    auto c = find_corners(v.image, board);
    if (c.empty())
      out.rejected.push_back(v.name);
    else
      corners.push_back(std::move(c)), used.push_back(v.name);
  }
  enough(corners.size(), out.rejected);
  const std::vector<std::vector<cv::Point3f>> object(corners.size(), board_points(board));
  cv::Mat K, D;
  std::vector<cv::Mat> rvecs, tvecs;
  out.rms = cv::calibrateCamera(object, corners, size, K, D, rvecs, tvecs);
  out.camera = from_cv(K, D, size);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i)
    out.views.push_back({used[i], view_rms(object[i], corners[i], rvecs[i], tvecs[i], K, D, sum2)});
  return out;
}

StereoCalibration calibrate_stereo(const std::vector<View>& left, const std::vector<View>& right,
                                   const Board& board) {
  check_board(board);
  if (left.size() != right.size())
    throw Error("stereo calibration: " + std::to_string(left.size()) + " left but " +
                std::to_string(right.size()) + " right images");
  std::vector<View> all = left;
  all.insert(all.end(), right.begin(), right.end());
  const cv::Size size = same_size(all);
  StereoCalibration out;
  std::vector<std::vector<cv::Point2f>> cl, cr;
  std::vector<std::string> used;
  for (std::size_t i = 0; i < left.size(); ++i) {
    auto a = find_corners(left[i].image, board), b = find_corners(right[i].image, board);
    if (a.empty() || b.empty())
      out.rejected.push_back(left[i].name + (a.empty() ? "" : " (right: " + right[i].name + ")"));
    else
      cl.push_back(std::move(a)), cr.push_back(std::move(b)), used.push_back(left[i].name);
  }
  enough(cl.size(), out.rejected);
  const std::vector<std::vector<cv::Point3f>> object(cl.size(), board_points(board));
  // Each camera alone first (the intrinsics), then the pair with them as the starting guess.
  cv::Mat K1, D1, K2, D2, R, T, E, F;
  std::vector<cv::Mat> rv, tv;
  out.left_rms = cv::calibrateCamera(object, cl, size, K1, D1, rv, tv);
  out.right_rms = cv::calibrateCamera(object, cr, size, K2, D2, rv, tv);
  out.rms = cv::stereoCalibrate(
      object, cl, cr, K1, D1, K2, D2, size, R, T, E, F, cv::CALIB_USE_INTRINSIC_GUESS,
      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-6));
  out.rig.left = from_cv(K1, D1, size), out.rig.right = from_cv(K2, D2, size);
  for (int r = 0; r < 3; ++r) {
    out.rig.T[r] = T.at<double>(r);
    for (int c = 0; c < 3; ++c) out.rig.R(r, c) = R.at<double>(r, c);
  }
  // Per pair: the board's pose from the left camera, the right one through R, T.
  for (std::size_t i = 0; i < cl.size(); ++i) {
    cv::Mat rvec, tvec;
    cv::solvePnP(object[i], cl[i], K1, D1, rvec, tvec);
    cv::Mat Rb;
    cv::Rodrigues(rvec, Rb);
    cv::Mat rvec_r, tvec_r = R * tvec + T;
    cv::Rodrigues(R * Rb, rvec_r);
    double sum2 = 0.0;
    view_rms(object[i], cl[i], rvec, tvec, K1, D1, sum2);
    view_rms(object[i], cr[i], rvec_r, tvec_r, K2, D2, sum2);
    out.views.push_back({used[i], std::sqrt(sum2 / double(2 * cl[i].size()))});
  }
  return out;
}

}  // namespace uwgrasp::camera
