#include "uwgrasp/grasp/frames.hpp"

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
