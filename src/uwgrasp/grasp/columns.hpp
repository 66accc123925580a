#pragma once
// What is under the rest of the scene. The object's unseen part is modelled (shape.hpp); the
// other things the camera saw are only their seen points, so a finger could pass through the
// unseen back of a neighbouring object: in a row of cans 1.5 cm apart, the top grasps closed
// along the row with a finger in the gap behind the cans' seen fronts. The same gravity prior
// the object's shape uses applies to them: what is seen rests on something below it, down to
// the seafloor. So each seen point of the rest of the scene stands for a column from it down to
// the seafloor plane, solid where the camera could not see (behind something it saw, as the
// object's assumed volume is): a gripper part at the grasp pose must not cut a solid stretch.
// Where the camera saw through a column (the seafloor under a handle), it is free.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/grasp/occlusion.hpp"
#include "uwgrasp/grasp/samplers.hpp"

namespace uwgrasp::grasp {

struct Solid;

// Points (L) above the seafloor plane, binned on a grid in the plane by their foot.
struct Columns {
  Eigen::Vector4f plane = Eigen::Vector4f::Zero();  // n.p + d = 0 in L, the camera on the + side
  Eigen::Vector3f u = Eigen::Vector3f::Zero(), v = Eigen::Vector3f::Zero();  // axes in the plane
  float cell = 0.02f, u0 = 0.0f, v0 = 0.0f;
  int nu = 0, nv = 0;
  std::vector<std::uint32_t> start;     // cell c holds points [start[c], start[c + 1])
  std::vector<Eigen::Vector3f> points;  // by cell
  std::vector<float> height;            // each point's height above the plane
  // What the camera saw: the nearest depth per bin, and the map from L to the camera frame.
  DepthMap seen;
  Eigen::Matrix3f camera_rotation = Eigen::Matrix3f::Identity();
  Eigen::Vector3f camera_offset = Eigen::Vector3f::Zero();
  float tolerance = 0.005f;  // m: a stretch nearer than this behind a seen depth is not hidden
  float step = 0.003f;       // m between the tests of a stretch inside a solid

  bool empty() const { return points.empty(); }
};

// The columns under `level_points` (the rest of the scene in L) down to `plane`; points on or
// below the plane stand for none. `seen` is every point the camera saw but the seafloor's, in
// the camera frame, and camera_from_level the map from L there.
Columns make_columns(std::span<const Eigen::Vector3f> level_points, const Eigen::Vector4f& plane,
                     std::span<const Eigen::Vector3f> seen, const Pose& camera_from_level,
                     float cell = 0.02f);

// Whether `solid` at the grasp pose of `c` cuts a column.
bool cuts_column(const Columns& cols, const Solid& solid, const Candidate& c);
// The same by testing every column: the oracle.
bool cuts_column_brute(const Columns& cols, const Solid& solid, const Candidate& c);

}  // namespace uwgrasp::grasp
