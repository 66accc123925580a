#pragma once
// Sparse stereo (thesis 3.3-3.6): keypoints (Harris corners, 3.3, or SIFT, 3.4) in both images,
// SIFT descriptors matched by nearest neighbour with Lowe's ratio test and a left-right cross-check
// (3.5), matches kept near their epipolar line (3.6), and each pair triangulated by the direct
// linear transform solved with an SVD (3.6.1).
#include <Eigen/Core>
#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "uwgrasp/camera/triangulate.hpp"

namespace uwgrasp::camera {

struct SparseConfig {
  std::string detector = "sift";  // "sift" or "harris"
  int max_features = 3000;        // per image
  double ratio = 0.75;            // best / second-best descriptor distance must be below this
  bool cross_check = true;        // the right keypoint's best match must be the left one back
  double epipolar_px = 1.5;       // px from the epipolar line (in the ideal right image)
  double max_range = 6.0;         // m: farther or behind-the-camera points are dropped
};

struct SparseMatch {
  Eigen::Vector2d left, right;  // raw pixels
  Eigen::Vector3d point;        // in the left camera's optical frame, m
  double epipolar = 0.0;        // px (in the ideal, or virtual, right image)
};

struct SparseResult {
  std::size_t left_keypoints = 0, right_keypoints = 0;
  std::size_t ratio_passed = 0, cross_checked = 0, epipolar_passed = 0;
  std::vector<SparseMatch> matches;  // the triangulated ones, by left keypoint order
};

// Throws Error naming the field for a bad config, or for images of different sizes. The
// triangulator carries the rig (and the port's Pinax cameras, if any).
SparseResult sparse_stereo(const cv::Mat& left, const cv::Mat& right, const Triangulator& tri,
                           const SparseConfig& cfg);

}  // namespace uwgrasp::camera
