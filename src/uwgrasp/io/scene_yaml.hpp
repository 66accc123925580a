#pragma once
// Scene files and the files `simulate` writes beside its images: truth.yaml (INTERFACE.md; also a
// valid scene file, so the evaluator rebuilds every mesh in its pose from it) and stereo.yaml.
//
// Scene file:
//   name: dock                         # optional, default: the file name
//   seafloor: {enabled: true, size: 30, color: [150, 135, 105], texture: 0.35}
//   vehicle: {position: [-0.9, 0, 0.5], rpy: [0, 0, 0]}     # body frame in W (z up)
//   camera_mount: {position: [0.2, 0, 0], rpy: [0, -0.6, 0]}  # optional, else grasp.frames.camera
//   water: {preset: coastal, attenuation: [0.6, 0.4, 0.55]}   # optional, any field of WaterConfig
//   port: {distance: 0.02, thickness: 0.012, n_glass: 1.49, n_water: 1.34}  # optional flat port
//   objects:
//     - name: handle
//       color: [210, 25, 25]
//       interest: true
//       pose: {position: [0, 0, 0], rpy: [0, 0, 0]}            # or orientation_xyzw
//       parts:
//         - {shape: box, size: [0.1, 0.02, 0.02], pose: {position: [0, 0, 0.05]}}
//         - {shape: cylinder, radius: 0.01, length: 0.2}
//         - {shape: torus, major: 0.1, radius: 0.012}
//         - {shape: sphere, radius: 0.05}
//         - {shape: mesh, file: meshes/valve.dae, scale: 1.0}  # relative to the scene file
#include <cstdint>
#include <string>

#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/sim/scene.hpp"

namespace uwgrasp::io {

// A built-in scene name, or a .yaml file. Throws Error naming the file and the key path
// (e.g. "objects[1].parts[0].size") for unknown keys, wrong types and impossible values.
sim::Scene load_scene(const std::string& name_or_path);
sim::Scene parse_scene(const std::string& yaml, const std::string& source, const std::string& base_dir);
// A flat port file (`simulate --port`, `stereo --port`): the keys of the scene's `port` block at
// its top level. Throws Error naming the file and key.
FlatPort load_port(const std::string& path);

// What truth.yaml records besides the scene.
struct TruthInfo {
  std::string sensor = "rgbd";
  std::uint64_t seed = 1;
  Pose world_from_camera = Pose::Identity();
  Mount camera_mount;
  sim::Intrinsics intrinsics;
  sim::CameraConfig camera;
  sim::WaterConfig water;
  sim::NoiseConfig noise;
};
std::string truth_yaml(const sim::Scene& scene, const TruthInfo& info);

// truth.yaml read back (`evaluate`): the scene and the camera that saw it. Throws Error naming
// the file and key for a missing or malformed camera block and for a mesh file that is missing.
struct Truth {
  sim::Scene scene;
  TruthInfo info;
};
Truth load_truth(const std::string& path);
// Stereo calibration: both cameras' K (no distortion: the rectified simulated pair), the right
// camera's rotation R and translation T from the left (OpenCV's stereoCalibrate convention).
std::string stereo_yaml(const sim::StereoFrame& s);

}  // namespace uwgrasp::io
