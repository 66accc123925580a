#pragma once
// Triangle meshes: the one geometry type the ray caster knows. Built-in primitives are
// tessellated finely enough that the faceting error stays below the sensor's depth noise.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "uwgrasp/core/pose.hpp"

namespace uwgrasp::sim {

struct Mesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
};

// Axis-aligned box of full size `size`, centred at the origin.
Mesh make_box(const Eigen::Vector3d& size);
// Cylinder along z, centred at the origin, with end caps.
Mesh make_cylinder(double radius, double length, int segments = 48);
// Torus around z (major radius R, tube radius r), centred at the origin.
Mesh make_torus(double major, double minor, int segments = 128, int sides = 32);
// Sphere by subdividing an icosahedron `levels` times (20 * 4^levels triangles).
Mesh make_sphere(double radius, int levels = 2);
// A square of side `size` in the z = 0 plane, normal +z, split into cells of `cell` metres.
Mesh make_plane(double size, double cell);

// Reads any format assimp knows (.dae, .obj, .stl, .ply, ...), node transforms applied, all parts
// merged, multiplied by `scale`. Throws Error naming the file if it is missing, does not parse or
// holds no triangles.
Mesh load_mesh(const std::string& path, double scale = 1.0);

void transform(Mesh& mesh, const Pose& pose);
void append(Mesh& to, const Mesh& from);

// Axis-aligned bounds {lo, hi}; both zero for an empty mesh.
std::array<Eigen::Vector3f, 2> bounds(const Mesh& mesh);
// Enclosed volume by the divergence theorem (exact for a closed, consistently oriented mesh).
double volume(const Mesh& mesh);
double area(const Mesh& mesh);

}  // namespace uwgrasp::sim
