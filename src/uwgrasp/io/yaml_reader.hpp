#pragma once
// Internal to io/: the strict YAML reading that scene.yaml, truth.yaml and port files share.
// Every error names the file and the key path.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/config_schema.hpp"
#include "uwgrasp/io/scene_yaml.hpp"

namespace uwgrasp::io::yaml {

struct Ctx {
  std::string source, base;
  [[noreturn]] void fail(const std::string& path, const std::string& msg) const {
    throw Error(source + ": " + path + ": " + msg);
  }
  void keys(const YAML::Node& n, const std::string& path, std::initializer_list<const char*> ok) const {
    if (!n.IsMap()) fail(path, "expected a mapping");
    for (const auto& kv : n) {
      const auto k = kv.first.as<std::string>();
      if (std::none_of(ok.begin(), ok.end(), [&](const char* a) { return k == a; }))
        fail(path.empty() ? k : path + "." + k, "unknown key");
    }
  }
  double num(const YAML::Node& n, const std::string& path, double lo, double hi) const {
    double v = 0;
    if (!n.IsScalar() || !YAML::convert<double>::decode(n, v)) fail(path, "expected a number");
    if (!std::isfinite(v) || v < lo || v > hi)
      fail(path, "value " + n.Scalar() + " is outside [" + shortest(lo) + ", " + shortest(hi) + "]");
    return v;
  }
  bool flag(const YAML::Node& n, const std::string& path) const {
    bool v = false;
    if (!n.IsScalar() || !YAML::convert<bool>::decode(n, v)) fail(path, "expected true or false");
    return v;
  }
  std::string text(const YAML::Node& n, const std::string& path) const {
    if (!n.IsScalar() || n.Scalar().empty()) fail(path, "expected a non-empty string");
    return n.Scalar();
  }
  Eigen::VectorXd vec(const YAML::Node& n, const std::string& path, int size, double lo, double hi) const {
    if (!n.IsSequence() || static_cast<int>(n.size()) != size)
      fail(path, "expected a list of " + std::to_string(size) + " numbers");
    Eigen::VectorXd v(size);
    for (int i = 0; i < size; ++i) v[i] = num(n[i], path + "[" + std::to_string(i) + "]", lo, hi);
    return v;
  }
  Eigen::Vector3d vec3(const YAML::Node& n, const std::string& path, double lo, double hi) const {
    return vec(n, path, 3, lo, hi);
  }
  Rgb8 color(const YAML::Node& n, const std::string& path) const {
    const Eigen::Vector3d c = vec3(n, path, 0, 255);
    return {static_cast<std::uint8_t>(std::lround(c.x())), static_cast<std::uint8_t>(std::lround(c.y())),
            static_cast<std::uint8_t>(std::lround(c.z()))};
  }
  Pose pose(const YAML::Node& n, const std::string& path) const {
    keys(n, path, {"position", "rpy", "orientation_xyzw"});
    Pose p = Pose::Identity();
    if (n["position"]) p.translation() = vec3(n["position"], path + ".position", -1e4, 1e4);
    if (n["rpy"] && n["orientation_xyzw"]) fail(path, "give rpy or orientation_xyzw, not both");
    if (n["rpy"]) p.linear() = quat_from_rpy(vec3(n["rpy"], path + ".rpy", -10, 10)).toRotationMatrix();
    if (n["orientation_xyzw"]) {
      const Eigen::VectorXd q = vec(n["orientation_xyzw"], path + ".orientation_xyzw", 4, -2, 2);
      if (q.norm() < 0.5) fail(path + ".orientation_xyzw", "is not a unit quaternion");
      p.linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix();
    }
    return p;
  }
  Mount mount(const YAML::Node& n, const std::string& path) const {
    const Pose p = pose(n, path);
    return {p.translation(), rpy_from_matrix(p.linear())};
  }
};

inline YAML::Node load_yaml(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(source + ": not valid YAML: " + e.what());
  }
}

inline std::string read_file(const std::string& path, const char* what) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open " + what);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// yaml-cpp throws its own exceptions for shapes the readers above do not expect (a complex key,
// a subscript of a scalar): one Error naming the file.
template <typename F>
auto refusing_yaml_errors(const std::string& source, F&& read) {
  try {
    return read();
  } catch (const YAML::Exception& e) {
    throw Error(source + ": malformed YAML (" + e.what() + ")");
  }
}

}  // namespace uwgrasp::io::yaml
