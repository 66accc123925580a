#pragma once
// Voxel-grid centroid downsampling (thesis 4.1.5).
#include <cstdint>
#include <vector>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::cloud {

struct VoxelConfig {
  bool enabled = false;
  float leaf = 0.0025f;          // m; 2.5 mm as in thesis 8.4
  std::uint32_t min_points = 1;  // voxels with fewer points are dropped
};

struct VoxelResult {
  Cloud cloud;  // one point per kept voxel, ordered by voxel index (x fastest, then y, then z)
  // For every input point, the output point that replaced it (kDropped if none).
  std::vector<std::uint32_t> voxel_of;
  static constexpr std::uint32_t kDropped = 0xFFFFFFFFu;
};

// Replaces the points of each voxel by their centroid; colours, normals (renormalised) and
// curvature are averaged, labels take the most frequent value. Voxel membership uses
// floor(p * (1/leaf)) in single precision so the voxels are exactly PCL's VoxelGrid voxels.
// Throws Error for a non-positive leaf or one so small that voxel indices would overflow.
VoxelResult voxel_grid(const Cloud& in, const VoxelConfig& cfg);

}  // namespace uwgrasp::cloud
