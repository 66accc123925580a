#pragma once
// Analytic solids seen by a pinhole camera for the symmetry tests (test_symmetry.cpp): a can
// standing upright, a cylinder in any pose, boxes turned and tilted; the oracle is the solid
// itself.
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <vector>

#include "uwgrasp/grasp/symmetry.hpp"

namespace uwgrasp::grasp::test_solids {
using V3 = Eigen::Vector3f;

// L: x forward, y right, z down; the camera at L's origin looking forward and 35 degrees down;
// the seafloor 0.45 m below it.
constexpr float kFloor = 0.45f;

inline Pose camera_from_level() {
  // Optical frame: z forward, x right, y down; pitched down about L's y.
  Eigen::Matrix3d level_from_optical;
  level_from_optical.col(0) = Eigen::Vector3d::UnitY();
  level_from_optical.col(1) = Eigen::Vector3d::UnitZ();
  level_from_optical.col(2) = Eigen::Vector3d::UnitX();
  const double pitch = 35.0 * std::numbers::pi / 180.0;
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()) * level_from_optical;
  return T.inverse();
}

// A convex solid as a signed-distance-like test and surface samples with outward normals.
struct Solid {
  std::vector<V3> surface, normals;  // L
};

inline Solid can(const V3& base_centre, float radius, float height) {
  Solid s;
  for (int k = 0; k <= 60; ++k)
    for (int a = 0; a < 240; ++a) {
      const float t = 2.0f * std::numbers::pi_v<float> * float(a) / 240.0f;
      const V3 n(std::cos(t), std::sin(t), 0.0f);
      s.surface.push_back(base_centre + radius * n - V3(0, 0, height * float(k) / 60.0f));
      s.normals.push_back(n);
    }
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j) {
      const V3 q(radius * float(i) / 40.0f, radius * float(j) / 40.0f, 0.0f);
      if (q.norm() > radius) continue;
      s.surface.push_back(base_centre + q - V3(0, 0, height));
      s.normals.push_back(-V3::UnitZ());
    }
  return s;
}

// A cylinder (a bottle's body) of `length` along the unit `axis` through `centre`, with its caps.
inline Solid cylinder(const V3& centre, const V3& axis, float radius, float length) {
  Solid s;
  const V3 u = axis.unitOrthogonal(), v = axis.cross(u);
  for (int k = 0; k <= 80; ++k)
    for (int a = 0; a < 240; ++a) {
      const float t = 2.0f * std::numbers::pi_v<float> * float(a) / 240.0f;
      const V3 n = std::cos(t) * u + std::sin(t) * v;
      s.surface.push_back(centre + radius * n + length * (float(k) / 80.0f - 0.5f) * axis);
      s.normals.push_back(n);
    }
  for (const float side : {-1.0f, 1.0f})
    for (int i = -30; i <= 30; ++i)
      for (int j = -30; j <= 30; ++j) {
        const float x = radius * float(i) / 30.0f, y = radius * float(j) / 30.0f;
        if (x * x + y * y > radius * radius) continue;
        s.surface.push_back(centre + side * 0.5f * length * axis + x * u + y * v);
        s.normals.push_back(side * axis);
      }
  return s;
}

// A box of `size` turned by R about its centre.
inline Solid box(const V3& centre, const V3& size, const Eigen::Matrix3f& R) {
  Solid s;
  const V3 h = 0.5f * size;
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i <= 50; ++i)
        for (int j = 0; j <= 50; ++j) {
          V3 q = V3::Zero();
          q[axis] = side * h[axis];
          q[u] = h[u] * (-1.0f + 2.0f * float(i) / 50.0f);
          q[v] = h[v] * (-1.0f + 2.0f * float(j) / 50.0f);
          V3 n = V3::Zero();
          n[axis] = side;
          s.surface.push_back(centre + R * q);
          s.normals.push_back(R * n);
        }
    }
  return s;
}

// An upright box turned by `yaw`, standing on base_centre.
inline Solid box(const V3& base_centre, const V3& size, float yaw) {
  return box(base_centre - V3(0, 0, 0.5f * size.z()), size,
             Eigen::AngleAxisf(yaw, V3::UnitZ()).toRotationMatrix());
}

// What the camera at L's origin sees of a convex solid: the surface facing it.
struct Sighted {
  std::vector<V3> level, normals, camera;
};
inline Sighted visible(const Solid& s) {
  Sighted v;
  const Pose T = camera_from_level();
  for (std::size_t i = 0; i < s.surface.size(); ++i) {
    if (s.normals[i].dot(-s.surface[i]) <= 1e-3f) continue;
    v.level.push_back(s.surface[i]);
    v.normals.push_back(s.normals[i]);
    v.camera.push_back((T * s.surface[i].cast<double>()).cast<float>());
  }
  return v;
}

// The seafloor z = kFloor in the camera frame, n.p + d = 0.
inline Eigen::Vector4f floor_in_camera() {
  const Pose T = camera_from_level();
  const Eigen::Vector3f n = (T.linear() * Eigen::Vector3d::UnitZ()).cast<float>();
  const Eigen::Vector3f p = (T * Eigen::Vector3d(0, 0, kFloor)).cast<float>();
  return {n.x(), n.y(), n.z(), -n.dot(p)};
}

// The scene's depth (the solid's seen side) with the seafloor: what symmetry is checked against.
struct Sight {
  SceneView v;
  const SceneView& view() const { return v; }
};
inline Sight sight_of(const Sighted& seen) {
  return {make_scene_view(seen.camera, floor_in_camera(), camera_from_level(), 0.003f, seen.level,
                          0.0015f)};
}

}  // namespace uwgrasp::grasp::test_solids
