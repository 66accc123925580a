#include "app/frame.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::app {

void add_frame_options(CLI::App& cmd, FrameOptions& o) {
  cmd.add_option("--camera-pose", o.camera_pose,
                 "The camera's pose in the cloud's frame, X,Y,Z,QX,QY,QZ,QW (optical axes: z "
                 "forward, x right, y down); overrides the PCD VIEWPOINT. Results are written in "
                 "the cloud's frame");
  cmd.add_option("--frame", o.frame,
                 "The cloud's frame: auto (the PCD VIEWPOINT when it is not the identity, else "
                 "the camera optical frame), camera (ignore VIEWPOINT), world (needs VIEWPOINT or "
                 "--camera-pose)")
      ->check(CLI::IsMember({"auto", "camera", "world"}));
}

Pose parse_camera_pose(const std::string& text, const std::string& what) {
  std::stringstream in(text);
  double v[7];
  bool ok = true;
  for (int i = 0; i < 7 && ok; ++i) {
    char comma = ',';
    ok = static_cast<bool>(in >> v[i]) && (i == 6 || (in >> comma && comma == ','));
  }
  ok = ok && (in >> std::ws).eof();
  const Eigen::Vector3d t(v[0], v[1], v[2]);
  const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
  if (!ok || !t.allFinite() || !q.coeffs().allFinite() || std::abs(q.norm() - 1.0) > 1e-3)
    throw Error(what + " '" + text + "': expected X,Y,Z,QX,QY,QZ,QW with a unit quaternion");
  return make_pose(t, q.normalized());
}


namespace {
// The cloud moved into the optical frame of a camera at T_FC.
Cloud in_camera(const Cloud& input, const Pose& T_FC) {
  Cloud c = input;
  c.viewpoint.setZero();
  c.orientation.setIdentity();
  if (!T_FC.isApprox(Pose::Identity())) c = transformed(c, T_FC.inverse());
  c.viewpoint.setZero(), c.orientation.setIdentity();
  return c;
}

std::string percent(double share) {
  char pct[32];
  std::snprintf(pct, sizeof pct, "%.0f %%", 100.0 * share);
  return pct;
}
}  // namespace

CameraCloud to_camera_frame(const Cloud& input, const FrameOptions& o, const std::string& name) {
  const bool has_viewpoint = !sensor_pose(input).isApprox(Pose::Identity());
  if (!o.camera_pose.empty() && o.frame == "camera")
    throw Error("--camera-pose and --frame camera contradict each other: the camera frame has the "
                "camera at its origin");
  CameraCloud out;
  Pose T_FC = Pose::Identity();
  if (!o.camera_pose.empty()) {
    T_FC = parse_camera_pose(o.camera_pose, "--camera-pose");
    out.summary = "camera pose from --camera-pose; results in the cloud's frame";
  } else if (has_viewpoint && o.frame != "camera") {
    T_FC = sensor_pose(input);
    out.summary = "camera pose from the cloud's VIEWPOINT; results in the cloud's frame";
    // Many published PCDs (PCL's own samples among them) carry a VIEWPOINT orientation that their
    // points do not follow. When the VIEWPOINT would put the points behind the camera and the
    // cloud as given has them in front, the cloud is in the camera frame (--frame world forces it).
    if (o.frame == "auto" && behind_camera(in_camera(input, T_FC)).share() >= 0.01 &&
        behind_camera(in_camera(input, Pose::Identity())).share() < 0.01) {
      T_FC = Pose::Identity();
      out.summary = "cloud in the camera optical frame (its VIEWPOINT would put the points behind the "
                    "camera, so it is ignored; --frame world uses it)";
    }
  } else if (o.frame == "world") {
    throw Error(name + ": --frame world needs the camera's pose: the cloud has no VIEWPOINT; give "
                "--camera-pose X,Y,Z,QX,QY,QZ,QW");
  } else {
    out.summary = "cloud in the camera optical frame";
  }
  const bool moved = !T_FC.isApprox(Pose::Identity());
  if (moved) out.frame = {"world", T_FC};
  out.cloud = in_camera(input, T_FC);
  const BehindCount behind = behind_camera(out.cloud);
  if (behind.share() >= 0.01)
    throw Error(name + ": " + percent(behind.share()) + " of the points lie behind the camera (z <= 0 in its optical "
                "frame), so the cloud is not in the camera's frame" +
                (moved ? " for this camera pose; check --camera-pose or the VIEWPOINT"
                       : "; give the camera's pose in the cloud's frame with --camera-pose "
                         "X,Y,Z,QX,QY,QZ,QW or a PCD VIEWPOINT (--frame world)"));
  return out;
}

}  // namespace uwgrasp::app
