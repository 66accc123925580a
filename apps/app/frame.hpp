#pragma once
// Clouds in any frame (detect, segment): the pipeline works in the camera optical frame
// (ARCHITECTURE.md "Frames"), so a cloud in a world or base frame is moved into it with the
// camera pose from --camera-pose or the PCD VIEWPOINT, and results go back to the cloud's frame.
#include <CLI/CLI.hpp>
#include <string>

#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/io/grasps_json.hpp"

namespace uwgrasp::app {

struct FrameOptions {
  std::string camera_pose;     // "X,Y,Z,QX,QY,QZ,QW": T_FC, the camera in the cloud's frame F
  std::string frame = "auto";  // auto | camera | world
};

// Adds --camera-pose and --frame.
void add_frame_options(CLI::App& cmd, FrameOptions& o);

// Parses X,Y,Z,QX,QY,QZ,QW (a finite position and a unit quaternion, normalised to 1e-3);
// throws Error naming `what` otherwise.
Pose parse_camera_pose(const std::string& text, const std::string& what);

struct CameraCloud {
  Cloud cloud;            // in the camera optical frame, viewpoint at the origin
  io::OutputFrame frame;  // the input cloud's frame and T_FC
  std::string summary;    // one line: where the camera pose came from
};

// The camera pose: --camera-pose if given, else the cloud's VIEWPOINT when it is not the
// identity (--frame auto or world), else the camera frame itself (--frame auto or camera);
// --frame world without a pose, or --camera-pose with --frame camera, is an error. Throws Error
// naming `name` and the options to use when 1 % or more of the finite points lie behind the
// camera (z <= 0 in its optical frame): such a cloud cannot be in the camera's frame.
CameraCloud to_camera_frame(const Cloud& input, const FrameOptions& o, const std::string& name);

}  // namespace uwgrasp::app
