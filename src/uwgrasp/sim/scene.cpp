#include "uwgrasp/sim/scene.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <set>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::sim {

namespace {
constexpr double kPi = std::numbers::pi;

void require(bool ok, const std::string& where, const char* what) {
  if (!ok) throw Error(where + ": " + what);
}
}  // namespace

const char* shape_name(ShapeKind k) {
  switch (k) {
    case ShapeKind::box: return "box";
    case ShapeKind::cylinder: return "cylinder";
    case ShapeKind::sphere: return "sphere";
    case ShapeKind::torus: return "torus";
    case ShapeKind::mesh: return "mesh";
  }
  return "?";
}

Pose world_from_body(const VehiclePose& v) {
  Pose T = Pose::Identity();
  T.translation() = v.position;
  // Rx(pi) turns the z-up world into the z-down body convention (Fossen) with x kept forward.
  T.linear() = Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix() *
               quat_from_rpy(v.rpy).toRotationMatrix();
  return T;
}

Mesh part_mesh(const Part& part) {
  const Shape& s = part.shape;
  Mesh m;
  switch (s.kind) {
    case ShapeKind::box:
      require((s.size.array() > 0).all() && s.size.allFinite(), "box", "size must be positive");
      m = make_box(s.size);
      break;
    case ShapeKind::cylinder:
      require(s.radius > 0 && s.length > 0 && std::isfinite(s.radius + s.length), "cylinder",
              "radius and length must be positive");
      m = make_cylinder(s.radius, s.length);
      break;
    case ShapeKind::sphere:
      require(s.radius > 0 && std::isfinite(s.radius), "sphere", "radius must be positive");
      m = make_sphere(s.radius, 3);
      break;
    case ShapeKind::torus:
      require(s.radius > 0 && s.major > s.radius && std::isfinite(s.major + s.radius), "torus",
              "needs 0 < radius < major");
      m = make_torus(s.major, s.radius);
      break;
    case ShapeKind::mesh:
      m = load_mesh(s.file, s.scale);
      break;
  }
  transform(m, part.pose);
  return m;
}

Mesh object_mesh(const SceneObject& object) {
  Mesh out;
  for (std::size_t i = 0; i < object.parts.size(); ++i) {
    try {
      append(out, part_mesh(object.parts[i]));
    } catch (const Error& e) {
      throw Error("object " + object.name + " part " + std::to_string(i) + ": " + e.what());
    }
  }
  transform(out, object.pose);
  return out;
}

void check_scene(const Scene& scene) {
  std::set<std::string> names;
  int interest = 0;
  for (const auto& o : scene.objects) {
    if (o.name.empty()) throw Error("scene " + scene.name + ": an object has no name");
    if (!names.insert(o.name).second) throw Error("scene " + scene.name + ": duplicate object " + o.name);
    if (o.parts.empty()) throw Error("object " + o.name + ": has no parts");
    if (!o.pose.matrix().allFinite()) throw Error("object " + o.name + ": pose is not finite");
    interest += o.interest ? 1 : 0;
  }
  if (interest > 1) throw Error("scene " + scene.name + ": more than one object of interest");
  if (!scene.vehicle.position.allFinite() || !scene.vehicle.rpy.allFinite())
    throw Error("scene " + scene.name + ": vehicle pose is not finite");
  if (scene.objects.empty() && !scene.seafloor.enabled)
    throw Error("scene " + scene.name + ": nothing to see (no objects, no seafloor)");
  if (scene.seafloor.enabled && !(scene.seafloor.size > 0))
    throw Error("scene " + scene.name + ": seafloor.size must be positive");
}

}  // namespace uwgrasp::sim
