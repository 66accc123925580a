#include "uwgrasp/grasp/frames.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::grasp {

namespace {
void require_finite(const Mount& m, const char* name) {
  if (!m.position.allFinite() || !m.rpy.allFinite())
    throw Error(std::string("frames.") + name + ": position and rpy must be finite");
}
}  // namespace

Frames make_frames(const FrameConfig& cfg) {
  require_finite(cfg.camera, "camera");
  require_finite(cfg.gripper, "gripper");
  if (!std::isfinite(cfg.capture_roll) || !std::isfinite(cfg.capture_pitch))
    throw Error("frames.capture_roll / capture_pitch must be finite");
  Frames f;
  f.level_from_camera =
      level_from_body(cfg.capture_roll, cfg.capture_pitch) * body_from_camera(cfg.camera);
  f.body_from_gripper = mount_pose(cfg.gripper);
  return f;
}

bool levels_from_floor(const FrameConfig& cfg) {
  using Level = FrameConfig::Level;
  return cfg.level_from_floor == Level::floor ||
         (cfg.level_from_floor == Level::automatic && cfg.capture_roll == 0.0 &&
          cfg.capture_pitch == 0.0);
}

void given_attitude(FrameConfig& cfg, double roll, double pitch) {
  cfg.capture_roll = roll;
  cfg.capture_pitch = pitch;
  if (cfg.level_from_floor == FrameConfig::Level::automatic)
    cfg.level_from_floor = FrameConfig::Level::attitude;
}

namespace {
// The plane's downward direction (away from the camera's side) in B; nullopt for a plane with no
// normal or through the camera.
std::optional<Eigen::Vector3d> floor_down(const Eigen::Vector4f& plane, const FrameConfig& cfg) {
  const Eigen::Vector3d n = plane.head<3>().cast<double>();
  const double norm = n.norm(), d = double(plane[3]);
  if (!(norm > 0.0) || !std::isfinite(norm) || !std::isfinite(d) || d == 0.0) return std::nullopt;
  // The camera (the origin) is on the side of d's sign: down is the normal away from it.
  const Eigen::Vector3d down_camera = (d > 0.0 ? -n : n) / norm;
  return body_from_camera(cfg.camera).linear() * down_camera;
}
}  // namespace

namespace {
// The angle between a downward direction in B and the vertical of cfg's own attitude.
double tilt_of(const Eigen::Vector3d& down, const FrameConfig& cfg) {
  const Eigen::Vector3d level =
      level_from_body(cfg.capture_roll, cfg.capture_pitch).linear() * down;
  return std::acos(std::clamp(level.z(), -1.0, 1.0));
}
}  // namespace

std::optional<double> floor_tilt(const Eigen::Vector4f& plane, const FrameConfig& cfg) {
  const auto down = floor_down(plane, cfg);
  if (!down) return std::nullopt;
  return tilt_of(*down, cfg);
}

std::optional<Attitude> attitude_from_floor(const Eigen::Vector4f& plane, const FrameConfig& cfg,
                                            double max_tilt) {
  const auto down = floor_down(plane, cfg);
  if (!down || tilt_of(*down, cfg) > max_tilt) return std::nullopt;
  // Fossen's gravity in the body frame, (-sin pitch, cos pitch sin roll, cos pitch cos roll),
  // solved for roll and pitch.
  return Attitude{std::atan2(down->y(), down->z()), std::asin(std::clamp(-down->x(), -1.0, 1.0))};
}

std::vector<Eigen::Vector3f> points_to_level(std::span<const Eigen::Vector3f> camera, const Frames& f) {
  const Eigen::Matrix3f R = f.level_from_camera.linear().cast<float>();
  const Eigen::Vector3f t = f.level_from_camera.translation().cast<float>();
  std::vector<Eigen::Vector3f> out;
  out.reserve(camera.size());
  for (const auto& p : camera) out.push_back(R * p + t);
  return out;
}

std::vector<Eigen::Vector3f> directions_to_level(std::span<const Eigen::Vector3f> camera,
                                                 const Frames& f) {
  const Eigen::Matrix3f R = f.level_from_camera.linear().cast<float>();
  std::vector<Eigen::Vector3f> out;
  out.reserve(camera.size());
  for (const auto& n : camera) out.push_back(R * n);
  return out;
}

Pose vehicle_pose(const Pose& level_from_gripper, const Frames& f) {
  return level_from_gripper * f.body_from_gripper.inverse();
}

}  // namespace uwgrasp::grasp
