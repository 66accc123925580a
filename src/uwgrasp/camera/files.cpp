#include "uwgrasp/camera/files.hpp"
#include "uwgrasp/camera/storage.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <fstream>
#include <opencv2/core.hpp>
#include <optional>
#include <sstream>
#include <vector>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::camera {

namespace {
std::string read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the calibration file");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Pinhole from_k_d(const std::vector<double>& K, const std::vector<double>& D, int width, int height,
                 const std::string& file, const std::string& kname, const std::string& dname) {
  if (K.size() != 9)
    throw Error(file + ": " + kname + " must hold 9 numbers (a 3 x 3 matrix), has " +
                std::to_string(K.size()));
  if (D.size() > 5)
    for (std::size_t i = 5; i < D.size(); ++i)
      if (D[i] != 0.0)
        throw Error(file + ": " + dname +
                    " has more than plumb_bob's 5 coefficients (k1 k2 p1 p2 k3)");
  Pinhole c;
  c.width = width, c.height = height;
  c.fx = K[0], c.fy = K[4], c.cx = K[2], c.cy = K[5];
  if (K[1] != 0.0 || K[3] != 0.0 || K[6] != 0.0 || K[7] != 0.0 || K[8] != 1.0)
    throw Error(file + ": " + kname + " must be [fx 0 cx; 0 fy cy; 0 0 1] (no skew)");
  for (std::size_t i = 0; i < std::min<std::size_t>(5, D.size()); ++i) c.distortion[i] = D[i];
  return c;
}

void emit_matrix(std::ostream& out, const char* key, const double* v, int n, const char* indent) {
  out << indent << key << ": [";
  for (int i = 0; i < n; ++i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v[i]);
    out << (i ? ", " : "") << buf;
  }
  out << "]\n";
}
}  // namespace

namespace {
// yaml-cpp and OpenCV throw their own exceptions for shapes of file the readers above do not
// expect (a complex key, a matrix whose data disagrees with rows x cols): one Error naming the file.
template <typename F>
auto refusing_library_errors(const std::string& path, F&& read) {
  try {
    return read();
  } catch (const YAML::Exception& e) {
    throw Error(path + ": malformed calibration file (" + e.what() + ")");
  } catch (const cv::Exception& e) {
    throw Error(path + ": malformed calibration file (" + e.err + ")");
  }
}

Pinhole read_camera_file(const std::string& path) {
  const std::string text = read_text(path);
  Pinhole c;
  if (opencv_storage(text)) {
    const Storage fs = open_storage(text, path);
    const auto K = storage_matrix(fs, {"camera_matrix", "cameraMatrix", "K", "M1", "K1"});
    if (!K)
      throw Error(path + ": missing the camera matrix (camera_matrix, cameraMatrix, K or M1)");
    const auto D = storage_matrix(fs, {"distortion_coefficients", "distCoeffs", "D", "D1"})
                       .value_or(std::vector<double>{});
    const auto [w, h] = storage_size(fs);
    c = from_k_d(*K, D, w, h, path, "camera_matrix", "distortion_coefficients");
  } else {
    const YAML::Node root = load_yaml(text, path);
    const char* kname = root["camera_matrix"] ? "camera_matrix" : "K";
    const char* dname = root["distortion_coefficients"] ? "distortion_coefficients" : "D";
    if (!root[kname]) throw Error(path + ": missing the camera matrix (camera_matrix or K)");
    const std::vector<double> D =
        root[dname] ? numbers(root[dname], path, dname) : std::vector<double>{};
    c = from_k_d(numbers(root[kname], path, kname), D,
                 integer(root["image_width"], path, "image_width"),
                 integer(root["image_height"], path, "image_height"), path, kname, dname);
  }
  check(c, path);
  return c;
}

StereoRig read_stereo_file(const std::string& path) {
  const std::string text = read_text(path);
  StereoRig s;
  std::vector<double> R, T;
  if (opencv_storage(text)) {
    const Storage fs = open_storage(text, path);
    const auto [w, h] = storage_size(fs);
    const auto need = [&](std::initializer_list<const char*> names, const char* what) {
      const auto m = storage_matrix(fs, names);
      if (!m) throw Error(path + ": missing " + what);
      return *m;
    };
    s.left = from_k_d(need({"M1", "K1"}, "M1 (the left camera matrix)"),
                      storage_matrix(fs, {"D1"}).value_or(std::vector<double>{}), w, h, path, "M1",
                      "D1");
    s.right = from_k_d(need({"M2", "K2"}, "M2 (the right camera matrix)"),
                       storage_matrix(fs, {"D2"}).value_or(std::vector<double>{}), w, h, path, "M2",
                       "D2");
    R = need({"R"}, "R"), T = need({"T"}, "T");
  } else {
    const YAML::Node root = load_yaml(text, path);
    const int w = integer(root["image_width"], path, "image_width"),
              h = integer(root["image_height"], path, "image_height");
    for (const char* side : {"left", "right"}) {
      const YAML::Node n = root[side];
      if (!n || !n.IsMap()) throw Error(path + ": missing " + side + " (its K and D)");
      const std::string k = std::string(side) + ".K", d = std::string(side) + ".D";
      if (!n["K"]) throw Error(path + ": missing " + k);
      (std::string(side) == "left" ? s.left : s.right) =
          from_k_d(numbers(n["K"], path, k),
                   n["D"] ? numbers(n["D"], path, d) : std::vector<double>{}, w, h, path, k, d);
    }
    if (!root["R"]) throw Error(path + ": missing R");
    if (!root["T"]) throw Error(path + ": missing T");
    R = numbers(root["R"], path, "R"), T = numbers(root["T"], path, "T");
  }
  if (R.size() != 9) throw Error(path + ": R must hold 9 numbers");
  if (T.size() != 3) throw Error(path + ": T must hold 3 numbers");
  s.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(R.data());
  s.T = Eigen::Map<const Eigen::Vector3d>(T.data());
  check(s, path);
  return s;
}
}  // namespace

Pinhole read_camera(const std::string& path) {
  return refusing_library_errors(path, [&] { return read_camera_file(path); });
}

StereoRig read_stereo(const std::string& path) {
  return refusing_library_errors(path, [&] { return read_stereo_file(path); });
}

std::string camera_yaml(const Pinhole& c, const std::string& name) {
  std::ostringstream out;
  const double K[9] = {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1};
  const double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double P[12] = {c.fx, 0, c.cx, 0, 0, c.fy, c.cy, 0, 0, 0, 1, 0};
  out << "# ROS camera_info (uwgrasp calibrate)\nimage_width: " << c.width
      << "\nimage_height: " << c.height << "\ncamera_name: " << name
      << "\ncamera_matrix:\n  rows: 3\n  cols: 3\n";
  emit_matrix(out, "data", K, 9, "  ");
  out << "distortion_model: plumb_bob\ndistortion_coefficients:\n  rows: 1\n  cols: 5\n";
  emit_matrix(out, "data", c.distortion.data(), 5, "  ");
  out << "rectification_matrix:\n  rows: 3\n  cols: 3\n";
  emit_matrix(out, "data", R, 9, "  ");
  out << "projection_matrix:\n  rows: 3\n  cols: 4\n";
  emit_matrix(out, "data", P, 12, "  ");
  return out.str();
}

std::string stereo_yaml(const StereoRig& s) {
  std::ostringstream out;
  out << "# uwgrasp stereo rig: x_right = R x_left + T (m)\nimage_width: " << s.left.width
      << "\nimage_height: " << s.left.height << "\n";
  for (const auto* side : {&s.left, &s.right}) {
    const double K[9] = {side->fx, 0, side->cx, 0, side->fy, side->cy, 0, 0, 1};
    out << (side == &s.left ? "left:\n" : "right:\n");
    emit_matrix(out, "K", K, 9, "  ");
    emit_matrix(out, "D", side->distortion.data(), 5, "  ");
  }
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> R = s.R;
  emit_matrix(out, "R", R.data(), 9, "");
  emit_matrix(out, "T", s.T.data(), 3, "");
  char buf[64];
  std::snprintf(buf, sizeof buf, "baseline: %.17g\n", s.baseline());
  out << buf;
  return out.str();
}

}  // namespace uwgrasp::camera
