#pragma once
// Whole-vehicle feasibility (beyond the thesis's collision box, 6.1): the gripper is bolted to
// the vehicle, so a grasp also needs room for the hull at the grasp pose, and for hull and
// gripper on the straight approach from a standoff along the gripper's approach axis. Checked
// against everything the camera saw - the seafloor plane the preprocessing removed and every
// remaining point, object included - not only the object.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <span>
#include <vector>

#include "uwgrasp/grasp/bvh.hpp"
#include "uwgrasp/grasp/columns.hpp"
#include "uwgrasp/grasp/feasibility.hpp"
#include "uwgrasp/grasp/frames.hpp"

namespace uwgrasp::grasp {

struct ReachConfig {
  bool enabled = true;
  // The hull as a box in B: the BlueROV2 Heavy's bounding box (Blue Robotics' Gazebo model,
  // 0.457 x 0.575 x 0.254 m) about the body origin.
  Eigen::Vector3d hull_size{0.457, 0.575, 0.254};
  Eigen::Vector3d hull_centre = Eigen::Vector3d::Zero();
  double standoff = 0.3;        // the approach starts this far back along the approach axis, m
  double margin = 0.02;         // grown on every side of the hull for positioning error, m
  double floor_tolerance = 0.0;   // parts may reach this far past the fitted seafloor plane, m
  // Detached clusters of points (gaps up to debris_gap) that fit in a box of this diagonal and
  // do not rest on the seafloor are suspended particles, not obstacles (debris.hpp); 0: none.
  double debris_size = 0.02;  // m
  double debris_gap = 0.01;   // m
  // The rest of the scene rests on the seafloor: the hidden stretch of the column under each of
  // its points is solid for the gripper's parts (columns.hpp). Off for a scene of overhangs.
  bool columns = true;
};

// The rest of the scene, in the camera frame.
struct Surroundings {
  std::span<const Eigen::Vector3f> points;  // the processed cloud, object included
  bool has_plane = false;                   // the plane the preprocessing removed
  Eigen::Vector4f plane = Eigen::Vector4f::Zero();  // n.p + d = 0, |n| = 1
  // Per point of `points` (or empty): 1 for a seen point of the rest of the scene, not of the
  // object, which stands for a column of solid down to the plane (columns.hpp).
  std::span<const char> rests{};
};

// An oriented box in the gripper frame G: p_G = centre + rotation * p_box, |p_box| <= half.
struct Solid {
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  Eigen::Matrix3f rotation = Eigen::Matrix3f::Identity();
  Eigen::Vector3f half = Eigen::Vector3f::Zero();
  Reject at_grasp = Reject::hull_collision;  // the reason when it hits at the grasp pose
};

// The solid's eight corners in L at offset t back along the approach (0: the grasp pose).
std::array<Eigen::Vector3f, 8> corners(const Solid& b, const Candidate& c, float t = 0.0f);

// The hull (from B through T_BG^-1, grown by the margin) first, then the gripper's solid parts.
// Throws Error for a non-positive hull size, a negative standoff, margin or tolerance, or a
// gripper mounted inside the hull.
std::vector<Solid> vehicle_solids(const Gripper& g, const Frames& f, const ReachConfig& cfg);

// The scene in L, ready for many checks: points under a hierarchy, and the plane oriented so the
// camera is on its positive side.
struct Obstacles {
  PointBvh bvh;  // empty() when the scene has no points
  bool has_plane = false;
  Eigen::Vector4f plane = Eigen::Vector4f::Zero();
  Columns columns;  // under the rest of the scene (empty without a plane or Surroundings::rests)
};
// Without the debris (suspended particles) cfg describes.
Obstacles make_obstacles(const Surroundings& s, const Frames& f, const ReachConfig& cfg = {});
// The surroundings' plane in L with the camera on its positive side, if there is one.
std::optional<Eigen::Vector4f> level_plane(const Surroundings& s, const Frames& f);

// Reject::none, or why the vehicle cannot take this grasp: hull_collision (hull at the grasp
// pose), scene_collision (a gripper part at the grasp pose hits a point that is not the object's,
// cuts a column under one, or goes through the seafloor), approach_blocked (hull or gripper on the way in).
Reject reach_check(const Obstacles& o, std::span<const Solid> solids, const Candidate& c,
                   const ReachConfig& cfg);
// reach_check against the seafloor plane alone (no scene points): a fraction of its cost, for
// screening many poses before the full check.
Reject reach_plane_check(const Obstacles& o, std::span<const Solid> solids, const Candidate& c,
                         const ReachConfig& cfg);
// Every point against every solid: the oracle for reach_check.
Reject reach_brute(std::span<const Eigen::Vector3f> level_points, const Obstacles& o,
                   std::span<const Solid> solids, const Candidate& c, const ReachConfig& cfg);

}  // namespace uwgrasp::grasp
