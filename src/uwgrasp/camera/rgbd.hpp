#pragma once
// RGB-D frames to clouds (thesis 3.7): a depth image registered to a colour image (same camera,
// same pixels) back-projected through the camera model into an organised XYZRGB cloud in the
// camera's optical frame.
#include <opencv2/core.hpp>
#include <string>

#include "uwgrasp/camera/model.hpp"
#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::camera {

// depth: CV_16UC1 in millimetres (0 = no depth; the ROS and OpenNI convention) or CV_32FC1 in
// metres (0, NaN or inf = no depth). colour: 8-bit BGR or grey of the same size, or empty (the
// cloud then has no colours). A pixel's ray comes from the camera's model, distortion included;
// its point is the ray scaled to the depth (z). Throws Error naming `what` for an image of
// another size than the camera's, a depth type other than those two, or sizes that differ.
Cloud rgbd_cloud(const cv::Mat& depth, const cv::Mat& colour, const Pinhole& camera,
                 const std::string& what = "RGB-D frame");

}  // namespace uwgrasp::camera
