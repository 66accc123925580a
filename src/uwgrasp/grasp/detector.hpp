#pragma once
// The detector pipeline: preprocess -> segment -> select object -> sample -> check -> score ->
// rank -> top K, with per-stage times and counts.
#include <cstdint>
#include <vector>

#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/timer.hpp"
#include "uwgrasp/grasp/feasibility.hpp"
#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/grasp/gripper.hpp"
#include "uwgrasp/grasp/occlusion.hpp"
#include "uwgrasp/grasp/reach.hpp"
#include "uwgrasp/grasp/samplers.hpp"
#include "uwgrasp/grasp/score.hpp"
#include "uwgrasp/grasp/shape.hpp"
#include "uwgrasp/segment/pipeline.hpp"

namespace uwgrasp::grasp {

struct GraspConfig {
  GripperConfig gripper;
  FrameConfig frames;
  SamplerConfig sampler;
  OcclusionConfig occlusion;
  ShapeConfig shape;
  ReachConfig reach;
  ScoreConfig score;
};

// What the grasp engine found on one object.
struct ObjectGrasps {
  Frames frames;
  SamplerKind sampler = SamplerKind::normal;  // the sampler that made the candidates (auto: chosen)
  std::size_t candidates = 0;
  RejectCounts rejections{};                   // rejections[none] = feasible candidates
  double max_inliers = 0;                      // q_i's denominator in effect
  ObjectShape shape;                           // the object's whole shape (empty when off)
  std::vector<Grasp> grasps;                   // ranked, at most score.top
  std::size_t feasible() const { return rejections[0]; }
};

// The grasp engine on a segmented object (camera frame, with normals). `leaf` is the voxel size
// for derived inlier maxima (0: the object's median point spacing). `around` is the rest of the
// scene for the whole-vehicle check (cfg.reach; without it only the object is an obstacle).
// Records "sample", "check", "reach" (with the shape and shadow checks), "score" and "robust"
// in `timer`. Throws Error for fewer
// than 3 points, missing normals, an invalid gripper, sampler, reach or weights, or a vehicle
// weight without a hold-cost function.
ObjectGrasps find_grasps(const Cloud& object, const GraspConfig& cfg, double leaf,
                         std::uint64_t seed, StageTimer& timer,
                         const Surroundings* around = nullptr);

struct Detection {
  segment::Scene scene;
  std::vector<Eigen::Vector3f> obstacles;  // the processed scene and the points outliers removed
  std::vector<char> rests;  // per obstacle: 1 for the rest of the processed scene (Surroundings::rests)
  std::size_t segment = 0;  // the selected object's segment
  // Whether the object was selected by colours restored as a fallback (preprocess.water.fallback):
  // no object had the colour as the camera saw it.
  bool restored_colours = false;
  // The capture attitude taken from the seafloor plane (FrameConfig::level_from_floor), when it
  // was asked for and a plane near enough to level was found; the result's frames use it.
  std::optional<Attitude> floor_attitude;
  Cloud object;             // its points, camera frame
  ObjectGrasps result;
  StageTimer timer;         // every stage, preprocessing to ranking
};

// The selected object's points (camera frame, with normals) in a segmented scene: the segment
// `cfg` selects and, with a merge radius, the segments gathered around it. Throws Error when the
// scene has no segment.
Cloud object_points(const segment::Scene& scene, const segment::ObjectConfig& cfg,
                    std::size_t& selected);

// The whole processed scene and the plane its preprocessing removed: what the whole-vehicle
// check treats as obstacles. Refers to `scene` and `points`, which must outlive it. With the
// input cloud, `points` also gets the points outlier removal dropped (a grazing face's sparse
// points are real surfaces: a finger must not sit in them); without it, only the processed cloud.
Surroundings surroundings(const segment::Scene& scene, std::vector<Eigen::Vector3f>& points,
                          const Cloud* input = nullptr);

Detection detect(const Cloud& input, const cloud::PreprocessConfig& pre,
                 const segment::SegmentConfig& seg, const GraspConfig& cfg, std::uint64_t seed);

// The same detection for a stream of frames (a node, a bag): `d` and `ws` are kept from frame
// to frame, so the segments reuse their buffers (segment_scene's stream form) and the
// detection's own lists keep their capacity. Same result as the call above. After a throw, `d`
// holds no result.
void detect(const Cloud& input, const cloud::PreprocessConfig& pre,
            const segment::SegmentConfig& seg, const GraspConfig& cfg, std::uint64_t seed,
            Detection& d, segment::Workspace& ws);

// T_CG of a grasp: the camera frame pose reported to users.
Pose camera_from_gripper(const Grasp& g, const Frames& f);

}  // namespace uwgrasp::grasp
