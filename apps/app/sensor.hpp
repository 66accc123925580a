#pragma once
// Images to clouds for the CLI: a stereo pair with its rig's calibration (optionally behind a
// flat port), or a depth + colour pair with its camera's, read from files and turned into the
// organised cloud the pipeline takes (thesis ch. 3).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "uwgrasp/camera/dense.hpp"
#include "uwgrasp/camera/sparse.hpp"
#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/timer.hpp"
#include "uwgrasp/grasp/shape.hpp"
#include "uwgrasp/sim/render.hpp"

namespace uwgrasp::app {

struct SensorOptions {
  std::vector<std::string> stereo;  // LEFT RIGHT
  std::vector<std::string> rgbd;    // DEPTH RGB
  std::string calib, camera, port;
  bool any() const { return !stereo.empty() || !rgbd.empty(); }
};

// Adds --stereo LEFT RIGHT, --rgbd DEPTH RGB, --calib, --camera and --port.
void add_sensor_options(CLI::App& cmd, SensorOptions& o);

// Reads an image for the stereo matcher (8-bit grey or BGR) or a depth image (16-bit mm or
// 32-bit float m); throws Error naming the file when it cannot be read or has another type.
cv::Mat read_image(const std::string& path);
cv::Mat read_depth(const std::string& path);

struct StereoCloud {
  camera::DenseFrame frame;
  std::string summary;  // the rig, the port, the disparities searched
};
// LEFT RIGHT with the rig of `calib` (and the port of `port`, if not empty): rectify, match,
// triangulate. Times the stages read, rectify, match and cloud into `timer`.
StereoCloud stereo_cloud(const std::string& left, const std::string& right,
                         const std::string& calib, const std::string& port,
                         const camera::DenseConfig& cfg, StageTimer& timer);
// DEPTH RGB with the camera of `camera_file`.
Cloud rgbd_cloud(const std::string& depth, const std::string& rgb, const std::string& camera_file,
                 StageTimer& timer);

// The rectified left image beside its disparity (near warm, far cool, no match black), with a
// title line: what `stereo --png` writes.
cv::Mat disparity_picture(const camera::DenseFrame& f, const std::string& title);

// The two images side by side with a line per triangulated match, coloured by depth.
cv::Mat matches_picture(const cv::Mat& left, const cv::Mat& right, const camera::SparseResult& r,
                        const std::string& title);

// A simulated stereo pair through the real pipeline: the simulator's rig (already rectified, no
// distortion) and its images matched as a camera's would be. With `port`, the rig sits behind it
// and Pinax corrects it. Records rectify, match and cloud in `timer` when given.
camera::DenseFrame simulated_stereo(const sim::StereoFrame& s, const camera::DenseConfig& cfg,
                                    const std::optional<FlatPort>& port = std::nullopt,
                                    StageTimer* timer = nullptr);

// Median |z - z_true| / z_true and completeness of a cloud against the true depth of the same
// pixels, over the pixels whose label is `label` (any label when negative) and whose true depth
// is at most `max_depth`.
struct DepthAccuracy {
  double median_error = 0.0, completeness = 0.0;
  std::size_t pixels = 0;
};
DepthAccuracy depth_accuracy(const Cloud& got, const sim::Frame& truth, int label,
                             double max_depth);

// The cloud of whichever input the options name (exactly one of a cloud file, --stereo, --rgbd);
// `name` is set to what to call it in output. A stereo pair's also gives the depth error of its
// matcher (camera::DenseFrame::depth_error; 0 otherwise), for grasp.shape.depth_error.
struct SensorCloud {
  Cloud cloud;
  double depth_error = 0.0;
};
SensorCloud sensor_input(const SensorOptions& o, const std::string& cloud_file,
                         const camera::DenseConfig& cfg, StageTimer& timer, std::string& name);

// A stereo matcher's cloud is smoother than it is right: its depth error (m at 1 m,
// camera::DenseFrame::depth_error; 0 for other sensors) floors the surface noise, unless the
// config already asks for more (grasp.shape.depth_error).
void use_matcher_error(grasp::ShapeConfig& shape, double depth_error);

}  // namespace uwgrasp::app
