#pragma once
// Gripper model (thesis 5.1, 6.1). Gripper frame G (ARCHITECTURE.md): origin at the centre of the
// closing region, x = approach (palm normal, palm -> fingertips), y = closing direction (finger
// to finger; the left finger is on -y, the right on +y), z = x cross y.
//
//        body (behind the palm, along the arm)   palm     fingers (at full aperture)
//   x: [-L/2 - d - b, -L/2 - d]             [-L/2 - d, -L/2]   [-L/2, L/2]
// The closing region is the volume the fingers sweep from open to closed: x in [-L/2, L/2],
// |y| <= A/2, |z| <= H/2 (H = finger height, 1.5 cm as in 8.4).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace uwgrasp::grasp {

struct GripperConfig {
  float max_aperture = 0.08f;    // A: inner distance between the fingers fully open, m
  float min_aperture = 0.0f;     // inner distance fully closed; thinner objects cannot be held
  float finger_length = 0.05f;   // L: palm face to fingertip, along x
  float finger_width = 0.01f;    // w: finger thickness along the closing direction y
  float finger_height = 0.015f;  // H: along z; also the closing region's height
  float palm_depth = 0.02f;      // d: palm thickness along x
  float palm_height = 0.04f;     // palm extent along z (its width spans both fingers)
  float body_length = 0.15f;     // b: gripper housing and arm behind the palm, along x
  float body_width = 0.06f;      // along y
  float body_height = 0.06f;     // along z
  // Free space the fingers need on each side to slide past the object under positioning error:
  // objects wider than max_aperture - 2 * clearance are rejected as too wide.
  float clearance = 0.005f;
};

// Axis-aligned box in the gripper frame.
struct Box {
  Eigen::Vector3f lo = Eigen::Vector3f::Zero(), hi = Eigen::Vector3f::Zero();
  bool contains(const Eigen::Vector3f& p) const {
    return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
  }
  Eigen::Vector3f centre() const { return 0.5f * (lo + hi); }
  Eigen::Vector3f half() const { return 0.5f * (hi - lo); }
  float volume() const { return (hi - lo).prod(); }
  // Corner k of 8: bit 0 picks hi.x over lo.x, bit 1 hi.y, bit 2 hi.z.
  Eigen::Vector3f corner(int k) const {
    return {(k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z()};
  }
};

// The solid parts, in the order the collision check reports them.
enum class Part { left_finger, right_finger, palm, body };
inline constexpr int kParts = 4;
const char* part_name(Part p);  // "left_finger", "right_finger", "palm", "body"

struct Gripper {
  GripperConfig config;
  Box closing;                       // the closing region
  std::array<Box, kParts> solids{};  // indexed by Part
  Box bounds;                        // encloses every part: the thesis's outer collision box
};

// Derives the boxes. Throws Error naming the field for a non-positive size, a negative minimum
// aperture, a minimum above the maximum, or a clearance that leaves no graspable width.
Gripper make_gripper(const GripperConfig& cfg);

// The gripper with every solid part grown by `margin` on each side (the closing region kept):
// what the collision check uses when the surface it checks against is uncertain by that much.
Gripper grow_solids(const Gripper& g, float margin);

// The edges of the solid parts (fingers, palm and, with `body`, the body behind the palm) at
// pose T (gripper frame in the output frame): 12 segments per box, for wireframe pictures and
// RViz markers.
std::vector<std::array<Eigen::Vector3f, 2>> gripper_edges(const Eigen::Isometry3d& T, const Gripper& g,
                                                          bool body = true);

// Largest width the gripper accepts at closure: max_aperture - 2 * clearance.
float max_grasp_width(const Gripper& g);

}  // namespace uwgrasp::grasp
