#pragma once
// The thesis's chapter-4 preprocessing chain as one thin composition of the cloud/ stages:
// invalid values -> (colour restoration) -> range crop -> voxel grid -> plane removal ->
// outliers -> normals.
// Outliers come after the plane: RANSAC is robust to them by design (4.1.4), and the statistics
// then describe the points that matter, at a fraction of the cost of a kNN over the seafloor.
#include <cstdint>
#include <string>
#include <vector>

#include "uwgrasp/cloud/color.hpp"
#include "uwgrasp/cloud/filters.hpp"
#include "uwgrasp/cloud/normals.hpp"
#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/outliers.hpp"
#include "uwgrasp/cloud/plane_noise.hpp"
#include "uwgrasp/cloud/ransac.hpp"
#include "uwgrasp/cloud/voxel.hpp"
#include "uwgrasp/core/timer.hpp"

namespace uwgrasp::cloud {

struct Workspace;  // workspace.hpp

struct PreprocessConfig {
  WaterColorConfig water;  // colour restoration, first after invalid values (off by default)
  RangeConfig range;
  OutlierConfig outliers;
  VoxelConfig voxel;
  PlaneConfig plane;
  NormalConfig normals;
  OrganisedConfig organised;
};

struct PreprocessCounts {
  std::size_t input = 0, finite = 0, in_range = 0, voxels = 0, plane = 0, after_outliers = 0,
              output = 0;
};

struct Preprocessed {
  Cloud cloud;  // what is left after every stage, with normals and curvature
  // For every input point, the index of the output point that represents it, or -1.
  std::vector<std::int32_t> output_of_input;
  // For every input point, true if the plane stage removed it (or the voxel that held it).
  std::vector<char> plane_of_input;
  PlaneResult plane;  // coefficients; inliers refer to the cloud the plane stage saw
  bool plane_is_face = false;  // the plane found was a face of the object, not a support (kept)
  NoiseModel noise;   // the depth noise measured on the plane (found only with noise_sigmas > 0)
  PreprocessCounts counts;
  // The kNN lists the normals were computed from (k = max(normals.k, share_k)), or on the
  // organised path the pixel-window lists, for later stages on the same cloud; empty in radius
  // mode.
  Neighbours neighbours;
  bool organised = false;  // which path ran (see preprocess below)
  // Organised path: the frame's depth noise in pixel footprints and the normals' half window it
  // chose (organised.hpp, normal_window); 0 on the k-d tree path.
  double noise_footprints = 0.0;
  std::uint32_t normal_half_window = 0;
  // When the points were moved onto quadratics fitted to their windows' ranges (organised.hpp,
  // move_onto_quadrics): the depth error left in them, sigma at 1 m growing with range^2, from
  // the noise the moves took out (MovedOntoQuadrics::left); 0 when not moved.
  // The moved points scatter far less than they err: the grasp engine's surface noise is
  // floored at this (grasp::detect, ShapeConfig::depth_error).
  double moved_depth_error = 0.0;
};

// Runs the chain; each stage's time is recorded in `timer` under its own name ("finite",
// "range", "voxel", "plane", "outliers", "normals"). Throws Error when the input has no finite
// point, when nothing survives a stage, or when a plane is required and none is found.
// share_k > normals.k keeps that many neighbours per point in the result.
// An organised frame (height > 1) with organised.enabled, no voxel grid and k-nearest normals
// takes the organised path: the same stages, with each point's neighbours the continuous pixels
// of its window (organised.hpp) instead of a k-d tree search; outliers.k, normals.k and share_k
// then give way to the window.
Preprocessed preprocess(const Cloud& in, const PreprocessConfig& cfg, std::uint64_t seed,
                        StageTimer& timer, std::size_t share_k = 0);
// The same into `out`, with `ws`'s buffers: a stream of frames preprocessed into one
// Preprocessed through one Workspace (workspace.hpp) asks the allocator for nothing on the
// organised path once both have grown to the frames. After a throw, `out` holds no result.
void preprocess(const Cloud& in, const PreprocessConfig& cfg, std::uint64_t seed, StageTimer& timer,
                Preprocessed& out, Workspace& ws, std::size_t share_k = 0);

// One line on which path preprocess takes for this cloud and why, e.g. "organised (640 x 480
// frame, 5 x 5 pixel windows)" or "k-d tree (unorganised cloud)", for the CLI to print.
std::string path_summary(const Cloud& in, const PreprocessConfig& cfg);
// The organised path's normal window and the noise that chose it, e.g. "7 x 7 pixel windows
// (depth noise 1.94 pixel footprints)", and when the points were moved onto their windows'
// range fits the error left in them ("; points moved onto their windows' range fits, 1.64 mm
// left at 1 m"); empty on the k-d tree path.
std::string normals_summary(const Preprocessed& p);

}  // namespace uwgrasp::cloud
