#pragma once
// grasps.json (INTERFACE.md): the detector's result with the full effective config and seed.
#include <nlohmann/json.hpp>
#include <string>

#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"

namespace uwgrasp::io {

// Poses are in the camera optical frame ("frame"); each grasp also carries its level-frame pose
// ("level") and the vehicle pose T_LB in the level frame. The vehicle score q_v and hold_cost
// (thruster utilisation of holding that pose's attitude) are null when no vehicle model priced
// the grasp (grasp.score.hold_cost empty).
// `frame` is the cloud's own frame when it came in another frame than the camera's (a world
// frame with the camera pose from the PCD VIEWPOINT, --camera-pose, or tf): poses, directions,
// contacts and the object's centroid are written in it, with the camera pose as "camera_pose".
struct OutputFrame {
  std::string name = "camera_optical";
  Pose from_camera = Pose::Identity();  // T_FC
};
nlohmann::json grasps_to_json(const grasp::Detection& d, const Config& cfg,
                              const std::string& input, const std::string& version,
                              const OutputFrame& frame = {});

// Writes the JSON atomically (no partial file), two-space indented, newline-terminated.
void write_json(const std::string& path, const nlohmann::json& j);

// One grasp read back from a grasps.json (`detect`'s, or `demo`'s with one entry per object).
struct GraspRecord {
  std::string object;   // the demo object's name, or "" for a detect file
  std::size_t rank = 1;
  Pose level_from_vehicle = Pose::Identity();  // T_LB the vehicle must reach
  Pose level_from_gripper = Pose::Identity();  // T_LG, whose x is the approach axis
  double score = 0;
  Config config;        // the detection's effective config, with `sets` applied
};
// Throws Error naming the file and field for a missing or malformed file, an unknown object, a
// rank beyond the grasps in the file, or a pose that is not finite. `object` empty: the first
// object of a demo file.
GraspRecord read_grasp(const std::string& path, std::size_t rank, const std::string& object,
                       const std::vector<std::string>& sets = {});

// Every grasp of a grasps.json from any detector (`evaluate`): the documented fields are read,
// others ignored. Per grasp: position, orientation_xyzw (a unit quaternion) and score are
// required. The gripper comes from config.grasp.gripper when the file has it (validated like
// any config), else the defaults. `object` picks a demo file's object (required there).
struct GraspList {
  std::string object;               // the demo object's name, or ""
  std::string frame = "camera_optical";  // or "world"
  grasp::GripperConfig gripper;
  bool gripper_from_file = false;
  struct Entry {
    std::size_t rank = 0;  // as written, or the position in the file (1-based)
    double score = 0.0;
    Pose pose = Pose::Identity();  // T_FG in `frame`
  };
  std::vector<Entry> grasps;  // best score first, ties by rank
};
GraspList read_grasp_list(const std::string& path, const std::string& object);

}  // namespace uwgrasp::io
