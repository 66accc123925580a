// uwgrasp calibrate IMAGES... [--right IMAGES...] --board COLSxROWS --square M --out FILE: Zhang's
// calibration (thesis 3.1) of one camera (ROS camera_info YAML out) or a stereo rig (uwgrasp's
// stereo file out), with the RMS reprojection error of every image and overall.
#include <cstdio>
#include <opencv2/imgcodecs.hpp>  // the IMREAD_ flags only: reading is viz::read_image's

#include "app/common.hpp"
#include "commands.hpp"
#include "uwgrasp/camera/calibrate.hpp"
#include "uwgrasp/camera/files.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/atomic_file.hpp"
#include "uwgrasp/viz/image_files.hpp"

namespace uwgrasp::app {

namespace {
struct CalibrateOptions {
  std::vector<std::string> images, right;
  std::string board = "9x6", out;
  double square = 1.0;
};

camera::Board parse_board(const std::string& text) {
  camera::Board b;
  const auto x = text.find('x');
  try {
    if (x == std::string::npos) throw std::invalid_argument("no x");
    std::size_t used = 0;
    b.cols = std::stoi(text.substr(0, x), &used);
    if (used != x) throw std::invalid_argument("cols");
    b.rows = std::stoi(text.substr(x + 1), &used);
    if (used != text.size() - x - 1) throw std::invalid_argument("rows");
  } catch (const std::exception&) {
    throw Error("--board '" + text + "': expected COLSxROWS inner corners, e.g. 9x6");
  }
  return b;
}

std::vector<camera::View> load(const std::vector<std::string>& paths) {
  std::vector<camera::View> views;
  for (const auto& p : paths) {
    views.push_back({p, viz::read_image(p, cv::IMREAD_GRAYSCALE)});
  }
  return views;
}

void print_camera(const char* what, const camera::Pinhole& c) {
  std::printf(
      "%s: %d x %d, fx %.3f fy %.3f cx %.3f cy %.3f, distortion k1 %.5f k2 %.5f p1 %.5f p2 %.5f k3 "
      "%.5f\n",
      what, c.width, c.height, c.fx, c.fy, c.cx, c.cy, c.distortion[0], c.distortion[1],
      c.distortion[2], c.distortion[3], c.distortion[4]);
}

void print_views(const std::vector<camera::ViewError>& views,
                 const std::vector<std::string>& rejected) {
  for (const auto& v : views) std::printf("  %-40s RMS %.4f px\n", v.name.c_str(), v.rms);
  for (const auto& r : rejected) std::printf("  %-40s board not found, left out\n", r.c_str());
}

int run_calibrate(const CalibrateOptions& o) {
  camera::Board board = parse_board(o.board);
  board.square = o.square;
  if (!(o.square > 0.0)) throw Error("--square must be positive (the side of one square, m)");
  if (o.right.empty()) {
    const camera::MonoCalibration c = camera::calibrate(load(o.images), board);
    print_views(c.views, c.rejected);
    print_camera("camera", c.camera);
    std::printf("RMS reprojection error %.4f px over %zu of %zu images\n", c.rms, c.views.size(),
                o.images.size());
    io::write_text(o.out, camera::camera_yaml(c.camera));
  } else {
    const camera::StereoCalibration c =
        camera::calibrate_stereo(load(o.images), load(o.right), board);
    print_views(c.views, c.rejected);
    print_camera("left ", c.rig.left);
    print_camera("right", c.rig.right);
    std::printf("T (%.5f, %.5f, %.5f), baseline %.5f (in the square's unit)\n", c.rig.T.x(),
                c.rig.T.y(), c.rig.T.z(), c.rig.baseline());
    std::printf(
        "RMS reprojection error: stereo %.4f px over %zu of %zu pairs (left alone %.4f, right "
        "alone %.4f)\n",
        c.rms, c.views.size(), o.images.size(), c.left_rms, c.right_rms);
    io::write_text(o.out, camera::stereo_yaml(c.rig));
  }
  std::printf("wrote %s\n", o.out.c_str());
  return 0;
}
}  // namespace

void add_calibrate_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners) {
  auto* cmd = app.add_subcommand(
      "calibrate", "Zhang calibration of a camera or a stereo rig from checkerboard images");
  auto o = std::make_shared<CalibrateOptions>();
  cmd->add_option("images", o->images, "Images of the board (the left camera's, for a rig)")
      ->required();
  cmd->add_option("--right", o->right,
                  "The right camera's images, in the same order: calibrate the stereo rig");
  cmd->add_option("--board", o->board, "Inner corners COLSxROWS (default 9x6)");
  cmd->add_option("--square", o->square, "Side of a square, m (default 1: results in squares)");
  cmd->add_option("--out", o->out,
                  "Calibration file to write (ROS camera_info YAML; a stereo file with --right)")
      ->required();
  runners.emplace_back(cmd, [o] { return run_calibrate(*o); });
}

}  // namespace uwgrasp::app
