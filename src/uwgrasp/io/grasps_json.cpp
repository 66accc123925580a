#include "uwgrasp/io/grasps_json.hpp"

#include <cmath>
#include <filesystem>

#include "uwgrasp/io/atomic_file.hpp"

namespace uwgrasp::io {

namespace {
using nlohmann::json;

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
// Unit quaternions: the grasp engine's poses are built from float axes, orthonormal to ~1e-7, and
// a quaternion taken from such a matrix is off unit length by as much (tf2 and others check it).
Eigen::Quaterniond unit(const Eigen::Matrix3d& R) { return Eigen::Quaterniond(R).normalized(); }
json quat(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q = unit(R);
  return {q.x(), q.y(), q.z(), q.w()};
}
json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json pose_json(const Pose& T) {
  return {{"position", vec(T.translation())},
          {"orientation_xyzw", quat(T.linear())},
          {"rpy", vec(rpy_from_matrix(T.linear()))}};
}

json grasp_json(const grasp::Grasp& g, const grasp::Frames& f, const Pose& T_FC, std::size_t rank) {
  const Pose T_CG = T_FC * grasp::camera_from_gripper(g, f);
  const Pose T_CL = T_FC * f.level_from_camera.inverse();
  json j;
  j["rank"] = rank;
  j["position"] = vec(T_CG.translation());
  // approach and closing are the columns of the rotation the quaternion gives, to double precision.
  const Eigen::Matrix3d R = unit(T_CG.linear()).toRotationMatrix();
  j["orientation_xyzw"] = quat(R);
  j["approach"] = vec(R.col(0));
  j["closing"] = vec(R.col(1));
  j["score"] = g.scores.total;
  j["scores"] = {{"normal", g.scores.normal},
                 {"orientation", g.scores.orientation},
                 {"contact_left", g.scores.contact_left},
                 {"contact_right", g.scores.contact_right},
                 {"inliers", g.scores.inliers},
                 {"vehicle", std::isfinite(g.hold_cost) ? json(g.scores.vehicle) : json(nullptr)}};
  j["inliers"] = g.inliers;
  j["width"] = g.width;
  j["contacts"] = {vec(T_CL * g.contacts[0]), vec(T_CL * g.contacts[1])};
  j["contact_seen"] = {g.contact_seen[0], g.contact_seen[1]};
  j["vehicle_pose"] = pose_json(g.level_from_vehicle);
  j["vehicle_pose"]["frame"] = "level";
  j["hold_cost"] = number_or_null(g.hold_cost);
  j["level"] = pose_json(g.level_from_gripper);
  j["antipodal"] = g.friction.ok;
  j["mu_required"] = number_or_null(g.friction.mu_required);
  j["robustness"] = g.robustness;        // robust mode: share of perturbed poses that hold on the model
  j["force_closure"] = g.force_closure;  // robust mode: q_fc
  j["candidate"] = g.candidate;
  return j;
}

json timing_json(const StageTimer& t) {
  const double pre = t.ms("finite") + t.ms("range") + t.ms("voxel") + t.ms("plane") +
                     t.ms("outliers") + t.ms("normals");
  return {{"preprocess", pre},
          {"segment", t.ms("segment") + t.ms("select")},
          {"sample", t.ms("sample")},
          {"check", t.ms("check") + t.ms("reach")},
          {"score", t.ms("score")},
          {"total", t.total_ms()}};
}
}  // namespace

json grasps_to_json(const grasp::Detection& d, const Config& cfg, const std::string& input,
                    const std::string& version, const OutputFrame& frame) {
  const auto& r = d.result;
  json j;
  j["uwgrasp_version"] = version;
  j["input"] = std::filesystem::path(input).filename().string();
  j["frame"] = frame.name;
  if (!frame.from_camera.isApprox(Pose::Identity())) {
    j["camera_pose"] = pose_json(frame.from_camera);
    j["camera_pose"].erase("rpy");
  }
  j["seed"] = cfg.seed;
  Config effective = cfg;  // with the attitude the grasps were found in (level_from_floor)
  if (d.floor_attitude) {
    effective.grasp.frames.capture_roll = d.floor_attitude->roll;
    effective.grasp.frames.capture_pitch = d.floor_attitude->pitch;
    effective.grasp.frames.level_from_floor = grasp::FrameConfig::Level::attitude;
  }
  j["config"] = to_json(effective);
  json rejected = json::object();
  for (int k = 1; k < grasp::kRejectKinds; ++k)
    rejected[grasp::reject_name(static_cast<grasp::Reject>(k))] = r.rejections[k];
  j["counts"] = {{"points_in", d.scene.pre.counts.input},
                 {"points_after_preprocess", d.scene.pre.counts.output},
                 {"object_points", d.object.size()},
                 {"candidates", r.candidates},
                 {"feasible", r.feasible()},
                 {"rejected", rejected}};
  j["timing_ms"] = timing_json(d.timer);
  j["object"] = {{"centroid", vec(frame.from_camera * centroid(d.object))},
                 {"points", d.object.size()},
                 {"segment", d.segment},
                 {"colours_restored", d.restored_colours}};
  j["sampler"] = grasp::sampler_name(r.sampler);
  j["max_inliers"] = r.max_inliers;
  j["grasps"] = json::array();
  for (std::size_t i = 0; i < r.grasps.size(); ++i)
    j["grasps"].push_back(grasp_json(r.grasps[i], r.frames, frame.from_camera, i + 1));
  return j;
}

void write_json(const std::string& path, const nlohmann::json& j) {
  write_text(path, j.dump(2) + "\n");
}

}  // namespace uwgrasp::io
