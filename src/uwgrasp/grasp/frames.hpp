#pragma once
// Frames (ARCHITECTURE.md): camera optical C, vehicle body B (x forward, y starboard, z down),
// level L (origin and heading of B at capture, roll = pitch = 0) and gripper G. Candidates are
// sampled and scored in L; results are reported in C and L.
#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "uwgrasp/core/pose.hpp"

namespace uwgrasp::grasp {

using uwgrasp::Mount;  // core/pose.hpp

struct FrameConfig {
  // The camera's forward-looking frame (x along the optical axis, like B) in B; all zero is a
  // camera looking straight ahead. Defaults: the BlueROV2's camera behind the front dome.
  Mount camera{Eigen::Vector3d(0.20, 0.0, 0.0), Eigen::Vector3d::Zero()};
  // T_BG: the gripper frame in B. Default: a gripper under the bottom panel whose closing region
  // sits 17 cm forward of the hull's front face (0.2285 m) and 4.3 cm below its bottom
  // (0.127 m) - measure yours. Approach along body x, fingers closing along body y, so the
  // vehicle's roll/pitch/yaw equal the gripper's (the thesis's assumption).
  Mount gripper{Eigen::Vector3d(0.40, 0.0, 0.17), Eigen::Vector3d::Zero()};
  double capture_roll = 0.0;   // vehicle attitude when the cloud was captured (IMU), rad
  double capture_pitch = 0.0;
  // Where L's level comes from (grasp.frames.level_from_floor). A frame that comes with no
  // attitude (a cloud file from a tabletop or hand-held camera) is best levelled by its seafloor
  // (support) plane; a vehicle's IMU gives capture_roll/pitch.
  enum class Level {
    automatic,  // "auto": the floor when no attitude is given (capture_roll = capture_pitch = 0,
                // the defaults, and no source called given_attitude), else capture_roll/pitch
    floor,      // "true": roll and pitch from the seafloor plane, in place of capture_roll/pitch
    attitude,   // "false": capture_roll/pitch as given
  };
  Level level_from_floor = Level::automatic;
};

// Whether the seafloor plane, when one is found, sets L's level under cfg (Level above).
bool levels_from_floor(const FrameConfig& cfg);

// A measured capture attitude (an IMU's, a simulated scene's vehicle): sets capture_roll/pitch and
// makes level_from_floor's "auto" keep them, even when both are zero.
void given_attitude(FrameConfig& cfg, double roll, double pitch);

// A support plane whose normal is further than this from the configured vertical is taken for a
// wall, not the floor, by level_from_floor (a camera pitched 37 degrees down at a table sees the
// table 37 degrees from a level camera's vertical; a wall is 90 degrees from it).
inline constexpr double kMaxFloorTilt = 1.0472;  // rad, 60 degrees

struct Attitude {
  double roll = 0.0, pitch = 0.0;  // rad, as capture_roll/pitch
};

// The angle between `plane`'s normal (camera frame, n.p + d = 0) and the vertical of cfg's own
// attitude, rad; nullopt for a plane with no normal or through the camera.
std::optional<double> floor_tilt(const Eigen::Vector4f& plane, const FrameConfig& cfg);

// The capture roll and pitch that make `plane` (camera frame, n.p + d = 0, as the plane stage
// gives it) level, with its camera side up: L's z along the plane's normal, away from the
// camera, through cfg.camera's mount. nullopt for a plane with no normal or through the camera,
// or one more than max_tilt from the vertical of cfg's own attitude.
std::optional<Attitude> attitude_from_floor(const Eigen::Vector4f& plane, const FrameConfig& cfg,
                                            double max_tilt = kMaxFloorTilt);

struct Frames {
  Pose level_from_camera;   // T_LC = T_LB(capture) * T_BC
  Pose body_from_gripper;   // T_BG
};

// Throws Error naming the field for a non-finite value.
Frames make_frames(const FrameConfig& cfg);

// Camera-frame points in L (T_LC p), and directions such as normals (R_LC n).
std::vector<Eigen::Vector3f> points_to_level(std::span<const Eigen::Vector3f> camera, const Frames& f);
std::vector<Eigen::Vector3f> directions_to_level(std::span<const Eigen::Vector3f> camera,
                                                 const Frames& f);

// The vehicle pose T_LB that puts the gripper at T_LG: T_LB = T_LG * T_BG^-1.
Pose vehicle_pose(const Pose& level_from_gripper, const Frames& f);

}  // namespace uwgrasp::grasp
