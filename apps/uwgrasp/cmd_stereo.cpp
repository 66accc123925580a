// uwgrasp stereo LEFT RIGHT --calib STEREO.yaml [--port PORT.yaml] --out CLOUD.pcd [--png FILE]:
// a stereo pair to an organised cloud in the left camera's optical frame (thesis 3.6, 3.8); with
// --sparse, the triangulated feature matches instead (3.3-3.6.1).
// uwgrasp rgbd DEPTH RGB --camera CAM.yaml --out CLOUD.pcd: a depth + colour pair (3.7).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/common.hpp"
#include "app/sensor.hpp"
#include "app/simulation.hpp"
#include "commands.hpp"
#include "uwgrasp/camera/files.hpp"
#include "uwgrasp/camera/sparse.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/pcd.hpp"
#include "uwgrasp/io/scene_yaml.hpp"

namespace uwgrasp::app {

namespace {
struct StereoOptions {
  CommonOptions common;
  std::string left, right, calib, port, out, png, detector = "sift";
  bool sparse = false;
};

struct RgbdOptions {
  std::string depth, rgb, camera, out;
};

void print_times(const StageTimer& t) {
  std::printf("stage times (ms):");
  for (const auto& st : t.stages()) std::printf(" %s %.1f |", st.name.c_str(), st.ms);
  std::printf(" total %.1f\n", t.total_ms());
}

std::size_t finite(const Cloud& c) {
  std::size_t n = 0;
  for (const auto& p : c.points) n += std::isfinite(p.z());
  return n;
}

// Keypoints matched left to right, triangulated: an unorganised cloud coloured from the left image.
int run_sparse(const StereoOptions& o, const io::Config& cfg) {
  StageTimer timer;
  timer.start("read");
  const camera::StereoRig rig = camera::read_stereo(o.calib);
  std::optional<FlatPort> port;
  if (!o.port.empty()) port = io::load_port(o.port);
  const cv::Mat l = read_image(o.left), r = read_image(o.right);
  const camera::Triangulator tri(rig, port, cfg.stereo.port_reference);
  camera::SparseConfig sc;
  sc.detector = o.detector, sc.max_range = cfg.stereo.max_range;
  timer.start("features, matching, triangulation");
  const camera::SparseResult res = camera::sparse_stereo(l, r, tri, sc);
  timer.stop();
  std::printf(
      "%s keypoints: %zu left, %zu right; ratio test %zu, cross-check %zu, epipolar (<= %.1f px) "
      "%zu, "
      "triangulated %zu\n",
      o.detector.c_str(), res.left_keypoints, res.right_keypoints, res.ratio_passed,
      res.cross_checked, sc.epipolar_px, res.epipolar_passed, res.matches.size());
  print_times(timer);
  if (res.matches.empty())
    throw Error(o.left + " and " + o.right + ": no feature matched (nothing written)");
  Cloud c;
  for (const auto& m : res.matches) {
    c.points.push_back(m.point.cast<float>());
    const int u = int(std::lround(m.left.x())), v = int(std::lround(m.left.y()));
    const std::uint8_t* px = l.ptr<std::uint8_t>(std::clamp(v, 0, l.rows - 1));
    const int x = std::clamp(u, 0, l.cols - 1);
    c.colors.push_back(l.channels() == 3 ? Rgb8{px[3 * x + 2], px[3 * x + 1], px[3 * x]}
                                         : Rgb8{px[x], px[x], px[x]});
  }
  c.width = std::uint32_t(c.size());
  io::save_cloud(o.out, c);
  std::printf("wrote %s\n", o.out.c_str());
  if (!o.png.empty()) {
    write_png(o.png, matches_picture(l, r, res, std::filesystem::path(o.left).filename().string()));
    std::printf("wrote %s\n", o.png.c_str());
  }
  return 0;
}

int run_stereo(const StereoOptions& o) {
  const Session session = open_session(o.common);
  if (o.sparse) return run_sparse(o, session.config);
  StageTimer timer;
  StereoCloud s = stereo_cloud(o.left, o.right, o.calib, o.port, session.config.stereo, timer);
  std::printf("stereo: %s\n", s.summary.c_str());
  const Cloud& c = s.frame.cloud;
  std::printf("cloud: %u x %u, %zu points with depth (%.1f %%), left camera optical frame\n",
              c.width, c.height, finite(c), 100.0 * double(finite(c)) / double(c.size()));
  print_times(timer);
  io::save_cloud(o.out, c);
  std::printf("wrote %s\n", o.out.c_str());
  // The file does not say it came from a matcher: its depth error goes with it by hand.
  std::printf(
      "depth error %.2f mm at 1 m (x depth^2; stereo.disparity_sigma %.2f px): detect this "
      "cloud with --set grasp.shape.depth_error=%.6f\n",
      1e3 * s.frame.depth_error, session.config.stereo.disparity_sigma, s.frame.depth_error);
  if (!o.png.empty()) {
    write_png(o.png, disparity_picture(s.frame, std::filesystem::path(o.left).filename().string()));
    std::printf("wrote %s\n", o.png.c_str());
  }
  return 0;
}

int run_rgbd(const RgbdOptions& o) {
  StageTimer timer;
  const Cloud c = rgbd_cloud(o.depth, o.rgb, o.camera, timer);
  std::printf("cloud: %u x %u, %zu points with depth (%.1f %%), camera optical frame\n", c.width,
              c.height, finite(c), 100.0 * double(finite(c)) / double(c.size()));
  print_times(timer);
  io::save_cloud(o.out, c);
  std::printf("wrote %s\n", o.out.c_str());
  return 0;
}
}  // namespace

void add_stereo_commands(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners) {
  auto* cmd = app.add_subcommand(
      "stereo", "A stereo pair to an organised cloud: rectify, match (SGBM), triangulate");
  auto o = std::make_shared<StereoOptions>();
  cmd->add_option("LEFT", o->left, "Left image")->required();
  cmd->add_option("RIGHT", o->right, "Right image")->required();
  cmd->add_option("--calib", o->calib, "The rig's calibration (uwgrasp's stereo file, or OpenCV's)")
      ->required();
  cmd->add_option("--port", o->port,
                  "The cameras sit behind this flat port (port.yaml): Pinax corrects it");
  cmd->add_option("--out", o->out, "Organised XYZRGB cloud to write (.pcd or .ply)")->required();
  cmd->add_option("--png", o->png,
                  "Draw the rectified left image and the disparity (or the matches) here");
  cmd->add_flag("--sparse", o->sparse, "Triangulate matched keypoints instead of matching densely");
  cmd->add_option("--detector", o->detector, "Keypoints for --sparse")
      ->check(CLI::IsMember({"sift", "harris"}));
  add_common(*cmd, o->common);
  runners.emplace_back(cmd, [o] { return run_stereo(*o); });

  auto* rgbd = app.add_subcommand(
      "rgbd", "A depth image and its registered colour image to an organised cloud");
  auto r = std::make_shared<RgbdOptions>();
  rgbd->add_option("DEPTH", r->depth, "Depth image: 16-bit millimetres or 32-bit float metres")
      ->required();
  rgbd->add_option("RGB", r->rgb, "Colour image registered to the depth image")->required();
  rgbd->add_option("--camera", r->camera,
                   "The camera's calibration (ROS camera_info or OpenCV YAML)")
      ->required();
  rgbd->add_option("--out", r->out, "Organised XYZRGB cloud to write (.pcd or .ply)")->required();
  runners.emplace_back(rgbd, [r] { return run_rgbd(*r); });
}

}  // namespace uwgrasp::app
