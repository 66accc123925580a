#pragma once
// A frame's buffers for preprocess on the organised path (preprocess.hpp), kept over a stream of
// frames: preprocessing frame after frame through one Workspace, into one Preprocessed, asks the
// allocator for nothing once the buffers have grown to the frames' sizes. Only the stages fill
// them; what they hold between calls is not an input.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "uwgrasp/cloud/normals.hpp"
#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/plane_noise.hpp"
#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::cloud {

// The plane stage's (plane_stage.hpp).
struct PlaneScratch {
  NoiseScratch noise;
  std::vector<std::pair<std::int64_t, std::int64_t>> cells;  // the inliers' plane cells
  std::vector<char> bits;                                    // the cells' bitmap
  std::vector<std::uint32_t> band;                           // the widened band's points
  std::vector<PointNormal> band_normals;
  std::vector<char> off;  // the band's points turned away
};

struct Workspace {
  Cloud next;                          // a filter's output, then swapped with the running cloud
  std::vector<std::uint32_t> kept;     // a filter's kept indices
  std::vector<std::int32_t> position;  // a kept point's new index
  std::vector<char> mask;              // the points a filter keeps
  std::vector<float> mean;             // the outlier statistic
  PixelMap map;                        // the pixels of the points in play
  WindowScratch window;
  PlaneScratch plane;
};

}  // namespace uwgrasp::cloud
