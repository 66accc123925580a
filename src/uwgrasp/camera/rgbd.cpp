#include "uwgrasp/camera/rgbd.hpp"

#include <cmath>
#include <limits>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::camera {

namespace {
std::string size_of(const cv::Mat& m) {
  return std::to_string(m.cols) + " x " + std::to_string(m.rows);
}

void check_images(const cv::Mat& depth, const cv::Mat& colour, const Pinhole& camera,
                  const std::string& what) {
  if (depth.empty()) throw Error(what + ": the depth image is empty");
  if (depth.type() != CV_16UC1 && depth.type() != CV_32FC1)
    throw Error(what + ": depth must be 16-bit (mm) or 32-bit float (m), one channel");
  if (depth.cols != camera.width || depth.rows != camera.height)
    throw Error(what + ": the depth image is " + size_of(depth) + ", the camera " +
                std::to_string(camera.width) + " x " + std::to_string(camera.height));
  if (!colour.empty() && colour.size() != depth.size())
    throw Error(what + ": the colour image is " + size_of(colour) + ", the depth image " +
                size_of(depth) + " (they must be registered)");
  if (!colour.empty() &&
      (colour.depth() != CV_8U || (colour.channels() != 1 && colour.channels() != 3)))
    throw Error(what + ": the colour image must be 8-bit grey or BGR");
}
}  // namespace

Cloud rgbd_cloud(const cv::Mat& depth, const cv::Mat& colour, const Pinhole& camera,
                 const std::string& what) {
  check(camera, what + " camera");
  check_images(depth, colour, camera, what);
  Cloud c;
  c.width = std::uint32_t(depth.cols), c.height = std::uint32_t(depth.rows);
  c.points.assign(depth.total(),
                  Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
  if (!colour.empty()) c.colors.resize(depth.total());
  const bool distorted = camera.distorted();
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      const std::size_t i = std::size_t(v) * c.width + std::size_t(u);
      if (!colour.empty()) {
        const std::uint8_t* px = colour.ptr<std::uint8_t>(v);
        c.colors[i] = colour.channels() == 3 ? Rgb8{px[3 * u + 2], px[3 * u + 1], px[3 * u]}
                                             : Rgb8{px[u], px[u], px[u]};
      }
      const double z = depth.type() == CV_16UC1 ? 0.001 * depth.at<std::uint16_t>(v, u)
                                                : double(depth.at<float>(v, u));
      if (!(z > 0.0) || !std::isfinite(z)) continue;
      // The ray through the pixel (eq. 3.1 inverted); z = 1 on it, so the point is ray * depth.
      const Eigen::Vector3d ray = distorted ? camera.unproject(Eigen::Vector2d(u, v))
                                            : Eigen::Vector3d((u - camera.cx) / camera.fx,
                                                              (v - camera.cy) / camera.fy, 1.0);
      c.points[i] = (ray * z).cast<float>();
    }
  }
  return c;
}

}  // namespace uwgrasp::camera
