#pragma once
// Preprocessing + segmentation as one call, with per-stage times (ARCHITECTURE.md data flow).
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/cloud/workspace.hpp"
#include "uwgrasp/core/timer.hpp"
#include "uwgrasp/segment/region_growing.hpp"
#include "uwgrasp/segment/select.hpp"

namespace uwgrasp::segment {

struct SegmentConfig {
  RegionConfig region;
  ColorConfig color;
  ObjectConfig object;
};

struct Scene {
  cloud::Preprocessed pre;          // the processed cloud and where each input point went
  Segmentation segmentation;        // over pre.cloud
  std::vector<SegmentInfo> info;    // per segment
  StageTimer timer;                 // finite, range, voxel, plane, outliers, normals, segment
};

Scene segment_scene(const Cloud& input, const cloud::PreprocessConfig& pre,
                    const SegmentConfig& seg, std::uint64_t seed);

// A frame's buffers, kept over a stream of frames.
struct Workspace {
  cloud::Workspace cloud;
  RegionScratch region;
};
// The same into `scene`, with `ws`'s buffers: a stream of organised frames segmented into one
// Scene through one Workspace asks the allocator for nothing once both have grown to the
// frames (without colour region growing, whose merging still makes its own lists). Same
// result as the call above. After a throw, `scene` holds no result.
void segment_scene(const Cloud& input, const cloud::PreprocessConfig& pre, const SegmentConfig& seg,
                   std::uint64_t seed, Scene& scene, Workspace& ws);

// Segment label of every input point (-1: none), through pre.output_of_input.
std::vector<std::int32_t> input_labels(const Scene& scene);

}  // namespace uwgrasp::segment
