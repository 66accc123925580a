#pragma once
// One view sees only the near side of an object (7.4.3): a gripper part placed just behind the
// visible surface may be inside the object's unseen body, where no point can reveal it. This
// check rejects a candidate whose solid parts lie in the camera's shadow of the object, less
// than `thickness` behind the visible surface - the thesis's assumption made explicit.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/grasp/gripper.hpp"
#include "uwgrasp/grasp/samplers.hpp"

namespace uwgrasp::grasp {

struct OcclusionConfig {
  bool enabled = false;  // superseded by the object's shape (shape.hpp); the thesis-era check
  float thickness = 0.03f;  // assumed depth of the object behind what the camera saw, m
  float tolerance = 0.003f; // parts may touch the surface from behind by this much, m
  float resolution = 0.003f;  // bin size of the depth map in normalised image units (~rad)
  float spacing = 0.01f;    // test points on the gripper parts, m (both faces of a finger)
};

// Nearest object depth per bin of normalised image coordinates (x/z, y/z) in the camera frame,
// dilated by one bin so that gaps between points do not read as free space.
struct DepthMap {
  float resolution = 0;
  int u0 = 0, v0 = 0, width = 0, height = 0;
  std::vector<float> depth;  // +inf where the object was not seen
  // Level l: the nearest and farthest seen depth per block of 2^l x 2^l bins, up to one block
  // for the whole map, so that a patch of part samples is cleared with four lookups.
  struct Level {
    int width = 0, height = 0;
    std::vector<float> lo, hi;  // +inf and -inf where nothing was seen
  };
  std::vector<Level> levels;
  float at(float x, float y) const;  // +inf outside the map
  float at_bin(int u, int v) const;  // the same by bin: u = floor(x / resolution)
  // Bounds {nearest, farthest} of the seen depths in bins [ua, ub] x [va, vb] (inclusive, the
  // same bins as at_bin), possibly over a few more bins around them; {+inf, -inf} when none.
  std::pair<float, float> range(int ua, int ub, int va, int vb) const;
};
DepthMap make_depth_map(std::span<const Eigen::Vector3f> camera_points, float resolution);

// Points on the surfaces of the gripper's solid parts in the gripper frame, in compact patches
// of about 4 x 4 samples with their bounding boxes.
struct PartSamples {
  struct Patch {
    Box bounds;
    std::uint32_t begin = 0, end = 0;  // into x, y, z
  };
  std::vector<float> x, y, z;  // each patch padded to a multiple of four with its last sample
  std::vector<Patch> patches;
};
PartSamples part_samples(const Gripper& g, float spacing);

// True when a part sample of the candidate (pose in L; camera_from_level maps L to C) lies in
// the object's shadow between tolerance and thickness behind the visible surface. A patch whose
// depths cannot fall in that band anywhere over the map's depths under it is skipped whole;
// cull = false tests every sample (the same answer: the oracle in tests).
bool occluded(const DepthMap& map, const PartSamples& samples, const Candidate& c,
              const Pose& camera_from_level, const OcclusionConfig& cfg, bool cull = true);

}  // namespace uwgrasp::grasp
