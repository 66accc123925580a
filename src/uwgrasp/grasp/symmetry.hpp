#pragma once
// The unseen back of an object from its mirror symmetry (after Bohg et al., "Mind the gap",
// ICRA 2011). One view shows the near side; most made objects - bottles, cans, boxes, tools,
// handles - are mirror-symmetric about a plane, and a curved back (a bottle's, a can's) is
// where a finger that trusts the visible side alone goes through the object or closes off its
// friction cone. A plane is a symmetry of what was seen when the seen points, mirrored about
// it, land where the camera could not see (hidden behind the seen surface) or on the seen
// surface itself (support), and almost never where the camera saw through to something farther
// away or under the seafloor (violations). The plane's offset is not free: mirrored about a
// plane in front of a curved object's widest section, the rim lands in seen free space;
// behind it, the object's near side lands behind its own shadow on the seafloor.
//
// The search (what "seen" means: sight.hpp): plane normals over azimuth (every `angle_step`)
// and tilt from the horizontal (up to `max_tilt`: objects lie in any pose), offsets across the
// object; each scored by support - violation_weight x violations on a sample of the points. The
// best plane is refined on finer normals and offsets (an upright one unless a tilted one scores
// `tilt_margin` better), aligned to the mirror pairs it makes, and kept when its violations and
// support pass the limits; with it the best plane perpendicular to it (a box's, a bottle's second
// symmetry: only its turn about the first plane's normal and its offset are searched), and the
// two turned together about their common line to where both fit best. The best plane of another
// family (30 degrees or more from the first) and its partner are found the same way; the set
// with more planes is kept, then the one with the higher summed score (a square box's diagonal
// plane outscores its face planes but has no partner within reach, and adds nothing behind).
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/grasp/sight.hpp"

namespace uwgrasp::grasp {

struct SymmetryConfig {
  bool enabled = true;
  float angle_step = 0.0873f;  // rad between coarse plane normals (5 degrees)
  float max_tilt = 0.524f;     // rad a plane's normal may rise from the horizontal (30 degrees)
  float tilt_margin = 0.1f;    // score a tilted plane needs above the best upright one
  float offset_step = 0.002f;  // m between coarse plane offsets
  std::uint32_t samples = 400;    // object points a plane is scored on
  float tolerance = 0.003f;       // m (plus noise_sigmas sigma of the surface noise): free space, surface
  // How far the tolerance grows with the measured surface noise. A wider tolerance lets a plane
  // slide further back before its mirror stops landing on the seen surface: at 3 the mustard
  // bottle's mirrored back comes out 5-17 mm too wide in noisy water. 1 fixes that bottle
  // (top-1 75 -> 95 % clear, 80 -> 90 % coastal, 20 seeds) but costs others as much (the turned
  // bottle 100 -> 85 %, the torque tool 90 -> 85 %); over all 54 cases the two are equal.
  float noise_sigmas = 3.0f;
  float violation_weight = 3.0f;  // a violation costs this much support
  float max_violations = 0.1f;    // share of the sample a kept plane may put in seen free space
  float min_support = 0.05f;      // share of the sample it must map onto the seen surface
  // The second plane exactly perpendicular to the first (two mirror planes of a box, a bottle, a
  // can, a tool are at 90 degrees); false: searched within 20 degrees of perpendicular, as before
  // (for objects with an odd-fold symmetry, such as a triangular prism).
  bool perpendicular = true;
};

struct MirrorPlane {
  Eigen::Vector3f normal = Eigen::Vector3f::UnitX();  // unit, L
  float offset = 0.0f;                                // n.p = offset on the plane
  float support = 0.0f, violations = 0.0f;            // shares of the sample
  float score = 0.0f;
  Eigen::Vector3f mirror(const Eigen::Vector3f& p) const { return p - 2.0f * (normal.dot(p) - offset) * normal; }
  Eigen::Vector3f mirror_direction(const Eigen::Vector3f& v) const { return v - 2.0f * normal.dot(v) * normal; }
};

// The object's symmetry planes (none, one, or two perpendicular ones; about perpendicular with
// `perpendicular` off), best first.
// `level`: the object's points in L (`tree`, when given: a k-d tree over them). `noise`: its
// surface noise (sigma, m). `down`: the seafloor's down in L (unit), which the normals' tilt and
// the upright preference are taken from: objects rest on the seafloor, so on a sloping one their
// planes are square to it, not to L. Deterministic.
std::vector<MirrorPlane> find_symmetry(std::span<const Eigen::Vector3f> level,
                                       const SceneView& view, float noise,
                                       const SymmetryConfig& cfg,
                                       const cloud::KdTree* tree = nullptr,
                                       const Eigen::Vector3f& down = Eigen::Vector3f::UnitZ());

// The points mirrored about the planes (and about both, for two), with their normals, kept
// where the camera could not have seen them (hidden): the object's completed back.
void mirror_points(std::span<const Eigen::Vector3f> level, std::span<const Eigen::Vector3f> normals,
                   std::span<const MirrorPlane> planes, const SceneView& view, float tolerance,
                   std::vector<Eigen::Vector3f>& points, std::vector<Eigen::Vector3f>& out_normals);

}  // namespace uwgrasp::grasp
