#pragma once
// Checkerboards rendered by the simulator for the calibration and refraction tests: a 9 x 6
// board at a known pose in front of the stereo rig at W's origin looking along +x, rendered at
// three times the size and area-averaged to 640 x 480 (a real sensor integrates over its pixels;
// the renderer samples each pixel once).
#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "uwgrasp/camera/calibrate.hpp"
#include "uwgrasp/sim/render.hpp"

namespace uwgrasp::test {

// Camera optical frame C at W's origin: z = W x, x = -W y, y = -W z.
inline Pose camera_along_x() {
  Pose p = Pose::Identity();
  p.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return p;
}

struct BoardPose {
  double distance, yaw, pitch, dy,
      dz;  // m, rad (about W z, W y, from facing the camera), m across the view
};

// Zhang's calibration set: near the image's centre and corners, turned up to 35 deg each way.
inline std::vector<BoardPose> calibration_poses() {
  return {{0.75, 0.0, 0.0, 0.0, 0.0},       {0.8, 0.6, 0.0, 0.05, 0.0},
          {0.8, -0.6, 0.0, -0.05, 0.0},     {0.8, 0.0, 0.6, 0.0, 0.04},
          {0.8, 0.0, -0.6, 0.0, -0.04},     {0.9, 0.45, 0.45, 0.15, 0.1},
          {0.9, -0.45, 0.45, -0.15, 0.1},   {0.9, 0.45, -0.45, 0.15, -0.1},
          {0.9, -0.45, -0.45, -0.15, -0.1}, {1.1, 0.3, -0.3, 0.25, 0.15},
          {1.1, -0.3, 0.3, -0.25, -0.15},   {1.1, 0.3, 0.3, -0.25, 0.15},
          {1.1, -0.3, -0.3, 0.25, -0.15},   {0.7, 0.3, 0.1, 0.0, 0.0}};
}

inline Pose board_pose(const BoardPose& b) {
  Pose p = Pose::Identity();
  p.linear() = (Eigen::AngleAxisd(b.yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(b.pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();  // the board's z towards the camera (W -x)
  p.translation() = Eigen::Vector3d(b.distance, b.dy, b.dz);
  return p;
}

// 9 x 6 inner corners of `square` m; the printed face at the part's z = +thickness / 2.
inline sim::Scene board_scene(const BoardPose& b, double square) {
  sim::Scene s;
  s.name = "board";
  s.seafloor.enabled = false;
  sim::Shape board{.kind = sim::ShapeKind::box,
                   .size = Eigen::Vector3d(12 * square, 9 * square, 0.005)};
  board.checker = {9, 6, square};
  s.objects.push_back({"board", {{board, Pose::Identity()}}, board_pose(b), {255, 255, 255}, true});
  return s;
}

// The inner corners in W (any order).
inline std::vector<Eigen::Vector3d> board_corners(const BoardPose& b, double square) {
  std::vector<Eigen::Vector3d> out;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 9; ++c)
      out.push_back(board_pose(b) *
                    Eigen::Vector3d((c - 4.0) * square, (r - 2.5) * square, 0.0025));
  return out;
}

inline cv::Mat grey_third(const std::vector<Rgb8>& rgb, int w, int h) {
  cv::Mat m(h, w, CV_8UC1), small;
  for (int i = 0; i < w * h; ++i) m.data[i] = rgb[std::size_t(i)].g;
  cv::resize(m, small, cv::Size(w / 3, h / 3), 0, 0, cv::INTER_AREA);
  return small;
}

// The rig's render config at three times 640 x 480, no water, no noise; `port` if set.
inline sim::RenderConfig board_render(const std::optional<FlatPort>& port = std::nullopt) {
  sim::RenderConfig cfg;
  cfg.noise.enabled = false;
  cfg.water.attenuation.setZero();
  cfg.water.veiling.setZero();
  cfg.camera.width = 1920, cfg.camera.height = 1440;
  cfg.port = port;
  return cfg;
}

// The 640 x 480 sensor's intrinsics.
inline sim::Intrinsics sensor_intrinsics() {
  sim::CameraConfig c;
  c.width = 640, c.height = 480;
  return sim::make_intrinsics(c);
}

inline std::pair<camera::View, camera::View> render_board(const BoardPose& b, double square,
                                                          const sim::RenderConfig& cfg,
                                                          const std::string& name) {
  const sim::World w(board_scene(b, square));
  const sim::StereoFrame f = sim::render_stereo(w, camera_along_x(), cfg, 1);
  const int W = f.intrinsics.width, H = f.intrinsics.height;
  return {{name, grey_third(f.left, W, H)}, {name, grey_third(f.right, W, H)}};
}

}  // namespace uwgrasp::test
