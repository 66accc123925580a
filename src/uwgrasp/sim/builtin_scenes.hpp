#pragma once
// Internal to sim/: what the built-in scene files share.
#include <optional>
#include <string>
#include <vector>

#include "uwgrasp/sim/scene.hpp"

namespace uwgrasp::sim {

// The camera of the built-in scenes: tilted 0.6 rad (34 deg) below the vehicle's bow.
Mount tilted_camera();
// A level vehicle placed so that the camera's optical axis passes through `target` at `distance`.
VehiclePose looking_at(const Eigen::Vector3d& target, double distance);

// The scenes of real objects' meshes (builtin_meshes.cpp): NAME, NAME_lying, NAME_turned.
std::vector<std::string> mesh_scene_names();
// The scene, nullopt for a name that is not a mesh scene; Throws Error if its mesh is missing.
std::optional<Scene> mesh_scene(const std::string& name);

}  // namespace uwgrasp::sim
