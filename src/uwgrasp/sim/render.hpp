#pragma once
// Ray-cast sensors (Embree): the RGB-D camera of the thesis (7.2) and a stereo rig, both seeing
// through the water model of water.hpp.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/core/port.hpp"
#include "uwgrasp/sim/camera.hpp"
#include "uwgrasp/sim/scene.hpp"
#include "uwgrasp/sim/water.hpp"

namespace uwgrasp::sim {

// Per-pixel truth labels (labels.png): which surface each pixel shows.
enum : std::uint16_t { kLabelWater = 0, kLabelSeafloor = 1, kLabelSnow = 2, kLabelFirstObject = 3 };

// The scene's meshes in an Embree BVH, built once and shared by any number of renders (also
// concurrent ones). Throws Error if a mesh cannot be built.
class World {
 public:
  explicit World(const Scene& scene);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const Scene& scene() const;
  std::size_t triangles() const;
  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

struct RenderConfig {
  CameraConfig camera;
  WaterConfig water;
  NoiseConfig noise;
  // The cameras behind a flat port (thesis 3.2): every primary ray bends at both faces of the
  // glass. The images then show what a real underwater camera sees; the RGB-D cloud stays the
  // true surface (an ideal depth sensor). Unset: the camera sees the water directly.
  std::optional<FlatPort> port;
};

struct Frame {
  Intrinsics intrinsics;
  Pose world_from_camera = Pose::Identity();
  Cloud cloud;                        // organised XYZRGB in C; NaN where there is no depth
  std::vector<Rgb8> rgb;              // row-major, width x height
  std::vector<std::uint16_t> depth;   // z in mm, 0 = no depth
  std::vector<std::uint16_t> labels;  // kLabel*, object i is kLabelFirstObject + i
};

struct StereoFrame {
  Intrinsics intrinsics;  // both cameras (rectified, identical)
  double baseline = 0.0;  // right camera at +baseline along the left camera's x
  Pose world_from_left = Pose::Identity();
  std::vector<Rgb8> left, right;
};

// T_WC: the vehicle pose, then the scene's camera mount (or `mount` when the scene has none).
Pose camera_pose(const Scene& scene, const Mount& mount);

// Renders one RGB-D frame. Same seed, same frame, at any thread count. Throws Error for an
// invalid configuration.
Frame render_rgbd(const World& world, const Pose& world_from_camera, const RenderConfig& cfg,
                  std::uint64_t seed);
StereoFrame render_stereo(const World& world, const Pose& world_from_left, const RenderConfig& cfg,
                          std::uint64_t seed);

}  // namespace uwgrasp::sim
