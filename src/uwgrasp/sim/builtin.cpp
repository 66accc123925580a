// The thesis's scenes (8.1, Figures 8.1 and 8.5). Dimensions keep the thesis's intent for the
// default gripper (80 mm aperture, 70 mm usable):
//   barbell: two 85 x 85 x 75 mm blocks (wider than the aperture) joined by a 120 mm bar of
//            25 x 25 mm: graspable only on the bar;
//   ring:    torus of 100 mm radius and 12 mm tube standing on a 20 mm pole, facing the camera:
//            nothing to grasp at its centroid, the ring graspable almost anywhere;
//   cross:   two 300 x 30 x 30 mm bars crossing, lying flat: tests the orientation terms.
// The same shapes, sampled analytically, are the grasp tests' fixtures (tests/fixtures).
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/builtin_scenes.hpp"

namespace uwgrasp::sim {

namespace {
using V = Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;
const Rgb8 kRed{210, 25, 25};

Pose at(const V& t, const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Pose p = Pose::Identity();
  p.translation() = t;
  p.linear() = R;
  return p;
}
Part box(const V& size, const V& centre) { return {Shape{.size = size}, at(centre)}; }

// The bar runs across the camera's view (along W's y) as in Figure 8.6.
SceneObject barbell(const V& where) {
  const Eigen::Matrix3d across = Eigen::AngleAxisd(kPi / 2, V::UnitZ()).toRotationMatrix();
  return {"barbell",
          {box(V(0.085, 0.085, 0.075), V(-0.1025, 0, 0.0375)),
           box(V(0.085, 0.085, 0.075), V(0.1025, 0, 0.0375)),
           box(V(0.12, 0.025, 0.025), V(0, 0, 0.0375))},
          at(where, across), kRed, false};
}

SceneObject ring(const V& where) {
  const Eigen::Matrix3d facing_x = Eigen::AngleAxisd(kPi / 2, V::UnitY()).toRotationMatrix();
  Part torus{Shape{.kind = ShapeKind::torus, .radius = 0.012, .major = 0.10}, at(V(0, 0, 0.35), facing_x)};
  Part pole{Shape{.kind = ShapeKind::cylinder, .radius = 0.01, .length = 0.238}, at(V(0, 0, 0.119))};
  return {"ring", {torus, pole}, at(where), kRed, false};
}

SceneObject cross(const V& where) {
  return {"cross",
          {box(V(0.30, 0.03, 0.03), V(0, 0, 0.015)), box(V(0.03, 0.30, 0.03), V(0, 0, 0.045))},
          at(where), kRed, false};
}

}  // namespace

// The camera of the built-in scenes looks 0.6 rad (34 deg) below the vehicle's bow, like the
// BlueROV2's tilting camera turned down to the seafloor.
Mount tilted_camera() { return {V(0.20, 0, 0), V(0, -0.6, 0)}; }

VehiclePose looking_at(const V& target, double distance) {
  VehiclePose v;
  v.rpy = V::Zero();
  v.position = V::Zero();
  const Mount mount = tilted_camera();
  const Pose wc = world_from_body(v) * body_from_camera(mount);
  const V axis = wc.linear().col(2);  // optical z in W
  v.position = target - distance * axis - wc.translation();
  return v;
}

namespace {
Scene single(SceneObject o, const V& target, double distance) {
  o.interest = true;
  Scene s{o.name, {o}, {}, looking_at(target, distance), tilted_camera()};
  return s;
}
}  // namespace

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> names = {"barbell", "ring", "cross", "thesis", "several"};
  for (const auto& n : mesh_scene_names()) names.push_back(n);
  return names;
}

Scene builtin_scene(const std::string& name) {
  if (name == "barbell") return single(barbell(V::Zero()), V(0, 0, 0.04), 0.75);
  if (name == "ring") return single(ring(V::Zero()), V(0, 0, 0.25), 0.9);
  if (name == "cross") return single(cross(V::Zero()), V(0, 0, 0.03), 0.8);
  if (name == "thesis") {
    Scene s{"thesis", {barbell(V(0, 0, 0)), ring(V(0.05, 0.42, 0)), cross(V(0.05, -0.42, 0))},
            {}, looking_at(V(0.02, 0, 0.1), 1.35), tilted_camera()};
    s.objects[0].interest = true;
    return s;
  }
  if (name == "several") {
    // Figure 8.5: several red objects; the barbell is the brightest red, so selection by colour
    // (7.4.2, highest intensity of the colour) must pick it.
    SceneObject ball{"ball", {{Shape{.kind = ShapeKind::sphere, .radius = 0.05}, at(V(0, 0, 0.05))}},
                     at(V(0.12, 0.32, 0)), Rgb8{150, 30, 30}, false};
    SceneObject drum{"drum",
                     {{Shape{.kind = ShapeKind::cylinder, .radius = 0.04, .length = 0.2},
                       at(V(0, 0, 0.04), Eigen::AngleAxisd(kPi / 2, V::UnitX()).toRotationMatrix())}},
                     at(V(0.15, -0.3, 0)), Rgb8{160, 40, 35}, false};
    SceneObject crate{"crate", {box(V(0.12, 0.12, 0.10), V(0, 0, 0.05))}, at(V(0.35, 0.05, 0)),
                      Rgb8{140, 35, 30}, false};
    SceneObject buoy{"buoy", {{Shape{.kind = ShapeKind::sphere, .radius = 0.06}, at(V(0, 0, 0.06))}},
                     at(V(0.3, -0.12, 0)), Rgb8{220, 190, 40}, false};
    SceneObject bb = barbell(V::Zero());
    bb.interest = true;
    return Scene{"several", {bb, ball, drum, crate, buoy}, {}, looking_at(V(0.1, 0, 0.05), 1.2),
                 tilted_camera()};
  }
  if (std::optional<Scene> s = mesh_scene(name)) return *s;
  std::string list;
  for (const auto& n : builtin_scene_names()) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown scene '" + name + "' (built-in scenes: " + list + ")");
}

}  // namespace uwgrasp::sim
