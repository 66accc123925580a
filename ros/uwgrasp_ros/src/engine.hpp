#pragma once
// The bridge between ROS 1 and the grasp engine. ROS 1's generated message headers do not compile
// as C++20 (they use std::allocator<void>::rebind, removed in C++20) and uwgrasp is C++20, so the
// files that include ROS headers are C++17 and talk to the engine only through this header: plain
// standard types, valid in both. engine.cpp (C++20) is the only side that sees uwgrasp's types.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::io {
struct Config;
}

namespace uwgrasp_ros {

// A rigid transform: position and unit quaternion (x, y, z, w).
struct Pose7 {
  std::array<double, 3> p{0, 0, 0};
  std::array<double, 4> q{0, 0, 0, 1};
};
Pose7 compose(const Pose7& a, const Pose7& b);  // a * b
Pose7 inverse(const Pose7& a);

struct PlainCloud {
  std::uint32_t width = 0, height = 1;  // height > 1: organised, row-major
  std::vector<float> xyz;               // 3 per point, NaN where there is no point
  std::vector<std::uint8_t> rgb;        // 3 per point, or empty
  std::size_t size() const { return xyz.size() / 3; }
};

// The frames of one capture (from tf and the IMU): unset fields keep the config's values.
struct Capture {
  std::optional<Pose7> ros_body_from_camera;  // tf base_frame -> the cloud's frame (REP 103 body)
  std::optional<std::array<double, 2>> roll_pitch;  // the vehicle's, rad (uwgrasp's convention)
};

// The vehicle's roll and pitch (uwgrasp's capture_roll/pitch) from the orientation of a ROS body
// frame (x forward, y left, z up) in an ENU world (an IMU's or odometry's, REP 145), quaternion
// x, y, z, w. Throws uwgrasp::Error for a non-finite or non-unit quaternion.
std::array<double, 2> roll_pitch_from(const std::array<double, 4>& q);

// ROS body frames (REP 103) and uwgrasp's body frame (Fossen: x forward, y starboard, z down)
// differ by a half turn about x.
Pose7 fossen_from_ros_body();

// The camera mount of uwgrasp's config (grasp.frames.camera: position and roll/pitch/yaw of the
// camera's forward frame in the Fossen body) from the optical frame's pose in a ROS body frame.
struct MountRpy {
  std::array<double, 3> position{}, rpy{};
};
MountRpy mount_from(const Pose7& ros_body_from_optical);

struct PlainGrasp {
  Pose7 pose;                            // gripper frame G in the cloud's frame
  std::array<double, 3> approach{}, closing{};
  double width = 0;
  std::array<std::array<double, 3>, 2> contacts{};
  std::array<bool, 2> contact_seen{};
  std::uint32_t inliers = 0;
  double score = 0, normal = 0, orientation = 0, contact_left = 0, contact_right = 0, inlier_score = 0;
  double vehicle_score = 0, hold_cost = 0;  // NaN when no vehicle model priced the grasp
  bool antipodal = false;
  double mu_required = 0, robustness = 0, force_closure = 0;
  Pose7 vehicle_pose;                    // body frame B (Fossen) to reach, in the cloud's frame
  std::array<double, 3> vehicle_rpy{};   // in the level frame, rad
  std::vector<std::array<float, 6>> edges;  // gripper wireframe, cloud's frame
};

struct PlainDetection {
  std::string warning;                   // why there is no grasp ("" when the engine ran through)
  std::string sampler;
  std::size_t points_in = 0, object_points = 0, candidates = 0, feasible = 0;
  std::array<double, 3> object_centroid{};
  std::vector<float> object_xyz;          // the object's points, 3 each
  std::vector<PlainGrasp> grasps;         // best first
  bool colours_restored = false;          // the object selected in restored colours (fallback)
  std::vector<std::pair<std::string, double>> stage_ms;
  double total_ms = 0;
  std::string json;                       // grasps.json (INTERFACE.md), compact, one line
};

// Where a reader writes a frame's points in place (Stream::frame), row-major.
struct FrameBuffers {
  float* xyz = nullptr;         // 3 floats a point; NaN where there is no point
  std::uint8_t* rgb = nullptr;  // 3 bytes a point (r, g, b), or null: the frame has no colours
};

// A stream's buffers, kept from frame to frame by a node or a bag reader: the cloud, the
// segments' workspace and the detection, so that a frame reuses the memory of the frames before
// it (grasp::detect's stream form). Opaque here: its contents are uwgrasp's C++20 types. One
// detection at a time may use a Stream.
class Stream {
 public:
  Stream();
  ~Stream();
  Stream(Stream&&) noexcept;
  Stream& operator=(Stream&&) noexcept;
  // The stream's cloud made width x height points (with colours or none; height 1: unorganised),
  // for a reader to fill in place before Engine::detect_frame: a message is copied once, into the
  // cloud the engine detects on, not first into a PlainCloud. Keeps the buffers' memory.
  FrameBuffers frame(std::uint32_t width, std::uint32_t height, bool colours);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  friend class Engine;
};

// The engine with its config: the same YAML as the CLI, then "a.b.c=value" overrides.
class Engine {
 public:
  // Throws uwgrasp::Error naming the file or key. `config_path` "": the compiled-in defaults.
  Engine(const std::string& config_path, const std::vector<std::string>& sets);
  ~Engine();
  Engine(const Engine&);
  Engine& operator=(const Engine&);
  // Applies overrides on top of the current config; throws uwgrasp::Error and keeps the config.
  void update(const std::vector<std::string>& sets);
  std::uint32_t threads() const;
  // Throws uwgrasp::Error for a cloud that cannot be in a camera optical frame (1 % or more of its
  // points behind the camera) or without a finite point; an engine failure on a good cloud (no
  // segment, no feasible grasp) is a PlainDetection with `warning` set. `input` names the cloud
  // in the JSON.
  PlainDetection detect(const PlainCloud& cloud, const Capture& capture, const std::string& input,
                        const std::string& version) const;
  // The same through a stream's buffers; the same result.
  PlainDetection detect(const PlainCloud& cloud, const Capture& capture, const std::string& input,
                        const std::string& version, Stream& stream) const;
  // The same on the stream's frame as its reader filled it (Stream::frame): what detect gives
  // for a PlainCloud of the same points.
  PlainDetection detect_frame(const Capture& capture, const std::string& input,
                              const std::string& version, Stream& stream) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  friend Engine make_engine(const uwgrasp::io::Config&);
};

}  // namespace uwgrasp_ros
