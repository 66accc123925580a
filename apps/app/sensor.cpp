#include "app/sensor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <opencv2/imgcodecs.hpp>  // the IMREAD_ flags only: reading is viz::read_image's
#include <opencv2/imgproc.hpp>

#include "uwgrasp/camera/files.hpp"
#include "uwgrasp/camera/rgbd.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/scene_yaml.hpp"
#include "uwgrasp/viz/image_files.hpp"
#include "uwgrasp/viz/picture.hpp"

namespace uwgrasp::app {

namespace {
std::string rig_summary(const camera::Rectification& r, bool port) {
  char line[256];
  std::snprintf(line, sizeof line,
                "rectified f %.1f px, baseline %.4f m, disparities %d-%d px (%.2f-%.2f m)%s",
                r.camera.fx, r.baseline, r.min_disparity, r.min_disparity + r.num_disparities - 1,
                r.camera.fx * r.baseline / std::max(1, r.min_disparity + r.num_disparities - 1),
                r.camera.fx * r.baseline / std::max(1, r.min_disparity),
                port ? ", flat port by Pinax" : "");
  return line;
}
}  // namespace

void add_sensor_options(CLI::App& cmd, SensorOptions& o) {
  cmd.add_option("--stereo", o.stereo,
                 "A stereo pair LEFT RIGHT instead of a cloud (needs --calib)")
      ->expected(2);
  cmd.add_option("--rgbd", o.rgbd,
                 "A depth image and its registered colour image DEPTH RGB (needs --camera)")
      ->expected(2);
  cmd.add_option("--calib", o.calib,
                 "The stereo rig's calibration (uwgrasp's stereo file or OpenCV's)");
  cmd.add_option("--camera", o.camera,
                 "The RGB-D camera's calibration (ROS camera_info or OpenCV YAML)");
  cmd.add_option("--port", o.port,
                 "The cameras sit behind this flat port (port.yaml): Pinax corrects it");
}

cv::Mat read_image(const std::string& path) {
  cv::Mat m = viz::read_image(path, cv::IMREAD_UNCHANGED);
  if (m.depth() != CV_8U) throw Error(path + ": the stereo matcher takes 8-bit images");
  if (m.channels() == 4) cv::cvtColor(m, m, cv::COLOR_BGRA2BGR);
  if (m.channels() != 1 && m.channels() != 3)
    throw Error(path + ": expected a grey or colour image");
  return m;
}

cv::Mat read_depth(const std::string& path) {
  cv::Mat m = viz::read_image(path, cv::IMREAD_ANYDEPTH);
  if (m.type() != CV_16UC1 && m.type() != CV_32FC1)
    throw Error(path + ": depth must be one channel of 16-bit millimetres or 32-bit float metres");
  return m;
}

StereoCloud stereo_cloud(const std::string& left, const std::string& right,
                         const std::string& calib, const std::string& port,
                         const camera::DenseConfig& cfg, StageTimer& timer) {
  if (calib.empty()) throw Error("--stereo needs --calib STEREO.yaml, the rig's calibration");
  timer.start("read");
  const camera::StereoRig rig = camera::read_stereo(calib);
  std::optional<FlatPort> flat;
  if (!port.empty()) flat = io::load_port(port);
  const cv::Mat l = read_image(left), r = read_image(right);
  if (l.size() != r.size())
    throw Error(right + ": " + std::to_string(r.cols) + " x " + std::to_string(r.rows) + ", but " +
                left + " is " + std::to_string(l.cols) + " x " + std::to_string(l.rows));
  timer.start("rectify maps");
  const camera::Rectification rect = camera::rectify(rig, cfg, flat);
  StereoCloud out;
  out.summary = rig_summary(rect, flat.has_value());
  out.frame = camera::dense_stereo(l, r, rect, cfg, left + " and " + right, &timer);
  return out;
}

Cloud rgbd_cloud(const std::string& depth, const std::string& rgb, const std::string& camera_file,
                 StageTimer& timer) {
  if (camera_file.empty())
    throw Error("--rgbd needs --camera CAM.yaml, the depth camera's calibration");
  timer.start("read");
  const camera::Pinhole cam = camera::read_camera(camera_file);
  const cv::Mat d = read_depth(depth), c = read_image(rgb);
  timer.start("cloud");
  Cloud out = camera::rgbd_cloud(d, c, cam, depth + " and " + rgb);
  timer.stop();
  return out;
}

cv::Mat disparity_picture(const camera::DenseFrame& f, const std::string& title) {
  const cv::Mat& d = f.disparity;
  double lo = 1e9, hi = 0.0;
  for (int v = 0; v < d.rows; ++v)
    for (int u = 0; u < d.cols; ++u)
      if (const float x = d.at<float>(v, u); std::isfinite(x))
        lo = std::min(lo, double(x)), hi = std::max(hi, double(x));
  cv::Mat grey(d.size(), CV_8UC1, cv::Scalar(0)), colour, left;
  for (int v = 0; v < d.rows; ++v)
    for (int u = 0; u < d.cols; ++u)
      if (const float x = d.at<float>(v, u); std::isfinite(x))
        grey.at<std::uint8_t>(v, u) = std::uint8_t(30 + 225 * (x - lo) / std::max(hi - lo, 1e-6));
  cv::applyColorMap(grey, colour, cv::COLORMAP_TURBO);
  colour.setTo(cv::Scalar(0, 0, 0), grey == 0);
  if (f.left_rectified.channels() == 1)
    cv::cvtColor(f.left_rectified, left, cv::COLOR_GRAY2BGR);
  else
    left = f.left_rectified;
  const int header = 34;
  cv::Mat out(d.rows + header, 2 * d.cols, CV_8UC3, cv::Scalar(255, 255, 255));
  left.copyTo(out(cv::Rect(0, header, d.cols, d.rows)));
  colour.copyTo(out(cv::Rect(d.cols, header, d.cols, d.rows)));
  std::size_t matched = 0;
  for (const auto& p : f.cloud.points) matched += std::isfinite(p.z());
  char line[256];
  std::snprintf(line, sizeof line,
                "%s: rectified left | disparity %.1f-%.1f px (warm near), %.0f %% matched",
                title.c_str(), hi >= lo ? lo : 0.0, hi,
                100.0 * double(matched) / double(std::max<std::size_t>(1, f.cloud.size())));
  cv::putText(out, line, {8, 23}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  return out;
}

cv::Mat matches_picture(const cv::Mat& left, const cv::Mat& right, const camera::SparseResult& r,
                        const std::string& title) {
  const int header = 34, w = left.cols;
  cv::Mat out(left.rows + header, 2 * w, CV_8UC3, cv::Scalar(255, 255, 255)), l, rr;
  if (left.channels() == 1)
    cv::cvtColor(left, l, cv::COLOR_GRAY2BGR), cv::cvtColor(right, rr, cv::COLOR_GRAY2BGR);
  else
    l = left, rr = right;
  l.copyTo(out(cv::Rect(0, header, w, left.rows)));
  rr.copyTo(out(cv::Rect(w, header, w, left.rows)));
  double lo = 1e9, hi = 0.0;
  for (const auto& m : r.matches) lo = std::min(lo, m.point.z()), hi = std::max(hi, m.point.z());
  cv::Mat ramp(1, 256, CV_8UC1), colours;
  for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(i) = std::uint8_t(i);
  cv::applyColorMap(ramp, colours, cv::COLORMAP_TURBO);
  // Every match a dot in both images; a line joins one in `step` (all of them hide the images).
  const std::size_t step = std::max<std::size_t>(1, r.matches.size() / 150);
  for (std::size_t i = 0; i < r.matches.size(); ++i) {
    const auto& m = r.matches[i];
    const int k = int(255 * (1.0 - (m.point.z() - lo) / std::max(hi - lo, 1e-9)));  // warm near
    const cv::Vec3b c = colours.at<cv::Vec3b>(k);
    const cv::Point a(int(std::lround(m.left.x())), int(std::lround(m.left.y())) + header);
    const cv::Point b(int(std::lround(m.right.x())) + w, int(std::lround(m.right.y())) + header);
    if (i % step == 0) cv::line(out, a, b, cv::Scalar(c[0], c[1], c[2]), 1, cv::LINE_AA);
    cv::circle(out, a, 2, cv::Scalar(c[0], c[1], c[2]), -1, cv::LINE_AA);
    cv::circle(out, b, 2, cv::Scalar(c[0], c[1], c[2]), -1, cv::LINE_AA);
  }
  char line[256];
  std::snprintf(line, sizeof line, "%s: %zu matches triangulated, depth %.2f-%.2f m (warm near)",
                title.c_str(), r.matches.size(), r.matches.empty() ? 0.0 : lo, hi);
  cv::putText(out, line, {8, 23}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  return out;
}

camera::DenseFrame simulated_stereo(const sim::StereoFrame& s, const camera::DenseConfig& cfg,
                                    const std::optional<FlatPort>& port, StageTimer* timer) {
  const auto& k = s.intrinsics;
  camera::StereoRig rig;
  rig.left = {k.width, k.height, k.fx, k.fy, k.cx, k.cy, {}};
  rig.right = rig.left;
  rig.T = Eigen::Vector3d(-s.baseline, 0.0, 0.0);
  return camera::dense_stereo(viz::rgb_image(s.left, k.width, k.height),
                              viz::rgb_image(s.right, k.width, k.height),
                              camera::rectify(rig, cfg, port), cfg, "simulated stereo pair", timer);
}

DepthAccuracy depth_accuracy(const Cloud& got, const sim::Frame& truth, int label,
                             double max_depth) {
  std::vector<double> rel;
  DepthAccuracy a;
  for (std::size_t i = 0; i < truth.cloud.size() && i < got.size(); ++i) {
    const float zt = truth.cloud.points[i].z();
    if (!std::isfinite(zt) || zt > max_depth || (label >= 0 && truth.labels[i] != label)) continue;
    ++a.pixels;
    if (const float z = got.points[i].z(); std::isfinite(z))
      rel.push_back(std::abs(double(z) - zt) / zt);
  }
  if (!rel.empty()) {
    std::nth_element(rel.begin(), rel.begin() + std::ptrdiff_t(rel.size() / 2), rel.end());
    a.median_error = rel[rel.size() / 2];
  } else {
    a.median_error = std::numeric_limits<double>::quiet_NaN();
  }
  a.completeness = a.pixels ? double(rel.size()) / double(a.pixels) : 0.0;
  return a;
}

SensorCloud sensor_input(const SensorOptions& o, const std::string& cloud_file,
                         const camera::DenseConfig& cfg, StageTimer& timer, std::string& name) {
  const int inputs = int(!cloud_file.empty()) + int(!o.stereo.empty()) + int(!o.rgbd.empty());
  if (inputs != 1)
    throw Error("give exactly one input: a cloud file, --stereo LEFT RIGHT or --rgbd DEPTH RGB");
  if (!o.stereo.empty()) {
    name = o.stereo[0];
    StereoCloud s = stereo_cloud(o.stereo[0], o.stereo[1], o.calib, o.port, cfg, timer);
    std::printf("stereo: %s\n", s.summary.c_str());
    return {std::move(s.frame.cloud), s.frame.depth_error};
  }
  name = o.rgbd[1];
  return {rgbd_cloud(o.rgbd[0], o.rgbd[1], o.camera, timer), 0.0};
}

void use_matcher_error(grasp::ShapeConfig& shape, double depth_error) {
  shape.depth_error = std::max(shape.depth_error, float(depth_error));
}

}  // namespace uwgrasp::app
