// truth.yaml and stereo.yaml writers (INTERFACE.md). truth.yaml is a scene file with the
// sensor's facts added, so load_scene() reads it back.
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <filesystem>

#include "uwgrasp/io/config_schema.hpp"
#include "uwgrasp/io/scene_yaml.hpp"

namespace uwgrasp::io {

namespace {
void seq(YAML::Emitter& e, const Eigen::VectorXd& v) {
  e << YAML::Flow << YAML::BeginSeq;
  for (Eigen::Index i = 0; i < v.size(); ++i) e << shortest(v[i]);
  e << YAML::EndSeq;
}
void color(YAML::Emitter& e, const Rgb8& c) {
  e << YAML::Flow << YAML::BeginSeq << int(c.r) << int(c.g) << int(c.b) << YAML::EndSeq;
}
void pose(YAML::Emitter& e, const Pose& p) {
  const Eigen::Quaterniond q(p.linear());
  e << YAML::BeginMap << YAML::Key << "position" << YAML::Value;
  seq(e, p.translation());
  e << YAML::Key << "orientation_xyzw" << YAML::Value;
  seq(e, Eigen::Vector4d(q.x(), q.y(), q.z(), q.w()));
  e << YAML::EndMap;
}
void shape(YAML::Emitter& e, const sim::Shape& s) {
  e << YAML::Key << "shape" << YAML::Value << sim::shape_name(s.kind);
  switch (s.kind) {
    case sim::ShapeKind::box:
      e << YAML::Key << "size" << YAML::Value;
      seq(e, s.size);
      if (s.checker.square > 0.0)
        e << YAML::Key << "checker" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "cols"
          << YAML::Value << s.checker.cols << YAML::Key << "rows" << YAML::Value << s.checker.rows << YAML::Key
          << "square" << YAML::Value << shortest(s.checker.square) << YAML::EndMap;
      break;
    case sim::ShapeKind::cylinder:
      e << YAML::Key << "radius" << YAML::Value << shortest(s.radius) << YAML::Key << "length"
        << YAML::Value << shortest(s.length);
      break;
    case sim::ShapeKind::sphere: e << YAML::Key << "radius" << YAML::Value << shortest(s.radius); break;
    case sim::ShapeKind::torus:
      e << YAML::Key << "major" << YAML::Value << shortest(s.major) << YAML::Key << "radius"
        << YAML::Value << shortest(s.radius);
      break;
    case sim::ShapeKind::mesh:
      e << YAML::Key << "file" << YAML::Value << std::filesystem::absolute(s.file).string()
        << YAML::Key << "scale" << YAML::Value << shortest(s.scale);
      break;
  }
}
void water(YAML::Emitter& e, const sim::WaterConfig& w) {
  e << YAML::BeginMap << YAML::Key << "preset" << YAML::Value << w.preset;
  e << YAML::Key << "attenuation" << YAML::Value;
  seq(e, w.attenuation);
  e << YAML::Key << "veiling" << YAML::Value;
  seq(e, w.veiling);
  e << YAML::Key << "snow_density" << YAML::Value << shortest(w.snow_density) << YAML::Key
    << "snow_radius" << YAML::Value << shortest(w.snow_radius) << YAML::Key << "snow_range"
    << YAML::Value << shortest(w.snow_range) << YAML::EndMap;
}
void objects(YAML::Emitter& e, const sim::Scene& s) {
  e << YAML::Key << "objects" << YAML::Value << YAML::BeginSeq;
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const auto& o = s.objects[i];
    e << YAML::BeginMap << YAML::Key << "name" << YAML::Value << o.name << YAML::Key << "label"
      << YAML::Value << int(sim::kLabelFirstObject + i) << YAML::Key << "color" << YAML::Value;
    color(e, o.color);
    e << YAML::Key << "interest" << YAML::Value << o.interest << YAML::Key << "pose" << YAML::Value;
    pose(e, o.pose);
    e << YAML::Key << "parts" << YAML::Value << YAML::BeginSeq;
    for (const auto& p : o.parts) {
      e << YAML::BeginMap;
      shape(e, p.shape);
      e << YAML::Key << "pose" << YAML::Value;
      pose(e, p.pose);
      e << YAML::EndMap;
    }
    e << YAML::EndSeq << YAML::EndMap;
  }
  e << YAML::EndSeq;
}
void camera(YAML::Emitter& e, const TruthInfo& t) {
  e << YAML::Key << "camera" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "world_from_camera" << YAML::Value;
  pose(e, t.world_from_camera);
  const auto& k = t.intrinsics;
  e << YAML::Key << "intrinsics" << YAML::Value << YAML::BeginMap << YAML::Key << "width"
    << YAML::Value << k.width << YAML::Key << "height" << YAML::Value << k.height << YAML::Key
    << "fx" << YAML::Value << shortest(k.fx) << YAML::Key << "fy" << YAML::Value << shortest(k.fy)
    << YAML::Key << "cx" << YAML::Value << shortest(k.cx) << YAML::Key << "cy" << YAML::Value
    << shortest(k.cy) << YAML::EndMap;
  e << YAML::Key << "min_range" << YAML::Value << shortest(t.camera.min_range) << YAML::Key
    << "max_range" << YAML::Value << shortest(t.camera.max_range) << YAML::Key << "baseline"
    << YAML::Value << shortest(t.camera.baseline) << YAML::EndMap;
}
}  // namespace

std::string truth_yaml(const sim::Scene& s, const TruthInfo& t) {
  YAML::Emitter e;
  e << YAML::BeginMap;
  e << YAML::Key << "name" << YAML::Value << s.name;
  e << YAML::Key << "sensor" << YAML::Value << t.sensor << YAML::Key << "seed" << YAML::Value << t.seed;
  camera(e, t);
  e << YAML::Key << "vehicle" << YAML::Value << YAML::BeginMap << YAML::Key << "position" << YAML::Value;
  seq(e, s.vehicle.position);
  e << YAML::Key << "rpy" << YAML::Value;
  seq(e, s.vehicle.rpy);
  e << YAML::EndMap << YAML::Key << "camera_mount" << YAML::Value << YAML::BeginMap << YAML::Key
    << "position" << YAML::Value;
  seq(e, t.camera_mount.position);
  e << YAML::Key << "rpy" << YAML::Value;
  seq(e, t.camera_mount.rpy);
  e << YAML::EndMap << YAML::Key << "water" << YAML::Value;
  water(e, t.water);
  if (s.port) {
    const FlatPort& p = *s.port;
    e << YAML::Key << "port" << YAML::Value << YAML::BeginMap << YAML::Key << "distance" << YAML::Value
      << shortest(p.distance) << YAML::Key << "thickness" << YAML::Value << shortest(p.thickness) << YAML::Key
      << "n_air" << YAML::Value << shortest(p.n_air) << YAML::Key << "n_glass" << YAML::Value
      << shortest(p.n_glass) << YAML::Key << "n_water" << YAML::Value << shortest(p.n_water) << YAML::EndMap;
  }
  e << YAML::Key << "noise" << YAML::Value << YAML::BeginMap << YAML::Key << "enabled" << YAML::Value
    << t.noise.enabled << YAML::Key << "sigma0" << YAML::Value << shortest(t.noise.sigma0)
    << YAML::Key << "sigma_k" << YAML::Value << shortest(t.noise.sigma_k) << YAML::EndMap;
  e << YAML::Key << "seafloor" << YAML::Value << YAML::BeginMap << YAML::Key << "enabled"
    << YAML::Value << s.seafloor.enabled << YAML::Key << "size" << YAML::Value
    << shortest(s.seafloor.size) << YAML::Key << "color" << YAML::Value;
  color(e, s.seafloor.color);
  e << YAML::Key << "texture" << YAML::Value << shortest(s.seafloor.texture) << YAML::EndMap;
  e << YAML::Key << "labels" << YAML::Value << YAML::BeginMap << YAML::Key << int(sim::kLabelWater)
    << YAML::Value << "water" << YAML::Key << int(sim::kLabelSeafloor) << YAML::Value << "seafloor"
    << YAML::Key << int(sim::kLabelSnow) << YAML::Value << "marine_snow" << YAML::EndMap;
  objects(e, s);
  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

std::string stereo_yaml(const sim::StereoFrame& s) {
  const auto& k = s.intrinsics;
  YAML::Emitter e;
  const auto K = [&] {
    e << YAML::BeginMap << YAML::Key << "K" << YAML::Value;
    seq(e, (Eigen::VectorXd(9) << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1).finished());
    e << YAML::Key << "D" << YAML::Value;
    seq(e, Eigen::VectorXd::Zero(5));
    e << YAML::EndMap;
  };
  e << YAML::BeginMap << YAML::Key << "image_width" << YAML::Value << k.width << YAML::Key
    << "image_height" << YAML::Value << k.height << YAML::Key << "left" << YAML::Value;
  K();
  e << YAML::Key << "right" << YAML::Value;
  K();
  // x_right = R x_left + T: the right camera sits at +baseline along x, so T = (-b, 0, 0).
  e << YAML::Key << "R" << YAML::Value;
  seq(e, (Eigen::VectorXd(9) << 1, 0, 0, 0, 1, 0, 0, 0, 1).finished());
  e << YAML::Key << "T" << YAML::Value;
  seq(e, Eigen::Vector3d(-s.baseline, 0, 0));
  e << YAML::Key << "baseline" << YAML::Value << shortest(s.baseline) << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

}  // namespace uwgrasp::io
