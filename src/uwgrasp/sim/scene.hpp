#pragma once
// Scene description (thesis 7.2, 8.1): objects made of primitive or mesh parts on a seafloor,
// watched by the camera of a vehicle. World frame W: z up, the seafloor is z = 0.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/core/port.hpp"
#include "uwgrasp/sim/mesh.hpp"
#include "uwgrasp/sim/water.hpp"

namespace uwgrasp::sim {

enum class ShapeKind { box, cylinder, sphere, torus, mesh };

// A calibration target printed on a box part's faces normal to its z: `cols` x `rows` inner
// corners of squares `square` m wide, centred in the part's x-y, black and white, a white margin
// around them (OpenCV's chessboard detector needs it). Off when square is 0.
struct Checker {
  int cols = 0, rows = 0;
  double square = 0.0;
};

struct Shape {
  ShapeKind kind = ShapeKind::box;
  Eigen::Vector3d size{0.1, 0.1, 0.1};  // box: full extents, m
  double radius = 0.05;                 // cylinder, sphere; torus: tube radius
  double length = 0.1;                  // cylinder, along its z
  double major = 0.1;                   // torus: centre of the tube to the axis, around its z
  std::string file{};                   // mesh: path (any format assimp reads)
  double scale = 1.0;                   // mesh: multiplies the file's coordinates
  Checker checker{};                    // box: a checkerboard printed on it
};

struct Part {
  Shape shape;
  Pose pose = Pose::Identity();  // in the object's frame
};

struct SceneObject {
  std::string name;
  std::vector<Part> parts;
  Pose pose = Pose::Identity();  // object frame in W
  Rgb8 color{200, 30, 30};
  bool interest = false;  // the object of interest (one per scene at most)
};

struct Seafloor {
  bool enabled = true;
  double size = 30.0;  // side of the square, m
  Rgb8 color{150, 135, 105};
  double texture = 0.35;  // albedo modulation amplitude (sand ripples; gives stereo texture)
};

// Where the vehicle is: body frame B (x forward, y starboard, z down, Fossen) in W is
// T_WB = translation * Rx(pi) * R(roll, pitch, yaw), so yaw turns to starboard seen from above.
struct VehiclePose {
  Eigen::Vector3d position{-0.9, 0.0, 0.5};
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
};

struct Scene {
  std::string name;
  std::vector<SceneObject> objects;
  Seafloor seafloor;
  VehiclePose vehicle;
  // The camera's mount on the vehicle when the scene needs its own (the built-in scenes tilt the
  // camera down towards the seafloor); otherwise the config's grasp.frames.camera.
  std::optional<Mount> camera_mount;
  // The scene's own water (a preset with any coefficient changed); otherwise the config's sim.water.
  std::optional<WaterConfig> water{};
  // The camera housing's flat port (thesis 3.2): set, the cameras see through it.
  std::optional<FlatPort> port{};
};

Pose world_from_body(const VehiclePose& v);

// The part's mesh in its object's frame / the whole object in W. Throws Error for degenerate
// dimensions (naming the object and part) or an unreadable mesh file.
Mesh part_mesh(const Part& part);
Mesh object_mesh(const SceneObject& object);

// Throws Error naming the object for an empty name, no parts, duplicate names, more than one
// object of interest, or non-finite poses.
void check_scene(const Scene& scene);

// Built-in scenes: barbell, ring, cross (each alone), thesis (all three, Figure 8.1), several
// (several red objects, Figure 8.5), and real objects' meshes from the data folder - sugar_box,
// mustard_bottle (YCB), t_bar, torque_tool, hot_stab (uuv_simulator) - each as NAME (upright),
// NAME_lying and NAME_turned. Throws Error listing the names for an unknown one, and naming the
// file for a mesh scene whose mesh is not in the data folder.
Scene builtin_scene(const std::string& name);
std::vector<std::string> builtin_scene_names();

// The folder holding the shared meshes: $UWGRASP_DATA, else the one beside the source tree.
std::string data_dir();

const char* shape_name(ShapeKind k);

}  // namespace uwgrasp::sim
