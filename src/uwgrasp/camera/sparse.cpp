#include "uwgrasp/camera/sparse.hpp"

#include <cmath>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::camera {

namespace {
// Grey, its contrast equalised locally (CLAHE): water flattens contrast with range, and both
// detectors' thresholds are relative to the image's own contrast.
cv::Mat grey(const cv::Mat& m) {
  cv::Mat g = m, out;
  if (m.channels() == 3) cv::cvtColor(m, g, cv::COLOR_BGR2GRAY);
  cv::createCLAHE(3.0, cv::Size(8, 8))->apply(g, out);
  return out;
}

// Keypoints and their SIFT descriptors: SIFT's own detector, or Harris corners (goodFeaturesToTrack
// with the Harris score, k = 0.04) described at a fixed 7 px scale.
void features(const cv::Mat& image, const SparseConfig& cfg, std::vector<cv::KeyPoint>& kp,
              cv::Mat& desc) {
  // A lower contrast threshold than SIFT's 0.04: underwater images are faint.
  const cv::Ptr<cv::SIFT> sift =
      cv::SIFT::create(cfg.detector == "sift" ? cfg.max_features : 0, 3, 0.01);
  if (cfg.detector == "sift") {
    sift->detectAndCompute(image, cv::noArray(), kp, desc);
    return;
  }
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(image, corners, cfg.max_features, 0.001, 5.0, cv::noArray(), 3, true,
                          0.04);
  if (!corners.empty())  // whole pixels to sub-pixel: the depth error scales with the pixel error
    cv::cornerSubPix(image, corners, cv::Size(2, 2), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 30, 0.01));
  kp.clear();
  for (const auto& c : corners) kp.emplace_back(c, 7.0f);
  sift->compute(image, kp, desc);
}

// Lowe's ratio test on the two nearest neighbours: best match index per query row, or -1.
std::vector<int> ratio_matches(const cv::Mat& query, const cv::Mat& train, double ratio) {
  std::vector<int> best(std::size_t(query.rows), -1);
  if (query.empty() || train.rows < 2) return best;
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(cv::NORM_L2).knnMatch(query, train, knn, 2);
  for (const auto& m : knn)
    if (m.size() == 2 && m[0].distance < ratio * m[1].distance)
      best[std::size_t(m[0].queryIdx)] = m[0].trainIdx;
  return best;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& t) {
  Eigen::Matrix3d s;
  s << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  return s;
}
}  // namespace

SparseResult sparse_stereo(const cv::Mat& left, const cv::Mat& right, const Triangulator& tri,
                           const SparseConfig& cfg) {
  if (cfg.detector != "sift" && cfg.detector != "harris")
    throw Error("sparse.detector must be sift or harris");
  if (cfg.max_features < 1) throw Error("sparse.max_features must be positive");
  if (!(cfg.ratio > 0.0 && cfg.ratio <= 1.0)) throw Error("sparse.ratio must be in (0, 1]");
  if (!(cfg.epipolar_px > 0.0)) throw Error("sparse.epipolar_px must be positive");
  if (left.empty() || left.size() != right.size())
    throw Error("sparse stereo: the images are empty or differ in size");
  const StereoRig& rig = tri.rig();
  SparseResult out;
  std::vector<cv::KeyPoint> kl, kr;
  cv::Mat dl, dr;
  features(grey(left), cfg, kl, dl);
  features(grey(right), cfg, kr, dr);
  out.left_keypoints = kl.size(), out.right_keypoints = kr.size();
  const std::vector<int> lr = ratio_matches(dl, dr, cfg.ratio);
  const std::vector<int> rl =
      cfg.cross_check ? ratio_matches(dr, dl, cfg.ratio) : std::vector<int>{};
  // Epipolar geometry of the undistorted normalised coordinates: x_r^T E x_l = 0, E = [T]x R.
  const Eigen::Matrix3d E = skew(rig.T) * rig.R;
  for (std::size_t i = 0; i < lr.size(); ++i) {
    if (lr[i] < 0) continue;
    ++out.ratio_passed;
    if (cfg.cross_check && rl[std::size_t(lr[i])] != int(i)) continue;
    ++out.cross_checked;
    const Eigen::Vector2d a(kl[i].pt.x, kl[i].pt.y),
        b(kr[std::size_t(lr[i])].pt.x, kr[std::size_t(lr[i])].pt.y);
    const auto xl = tri.left_ray(a), xr = tri.right_ray(b);
    if (!xl || !xr) continue;
    const Eigen::Vector3d line = E * *xl;  // in the right camera's normalised plane
    const double epi =
        std::abs(xr->dot(line)) / std::max(line.head<2>().norm(), 1e-300) * rig.right.fx;
    if (epi > cfg.epipolar_px) continue;
    ++out.epipolar_passed;
    const auto X = tri.point(a, b);
    if (!X || !(X->z() > 0.0) || X->z() > cfg.max_range) continue;
    out.matches.push_back({a, b, *X, epi});
  }
  return out;
}

}  // namespace uwgrasp::camera
