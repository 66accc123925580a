#pragma once
// Region-growing segmentation (thesis 4.2.2), with the optional colour criterion and the
// distance + mean-colour merging step of the RGB variant.
#include <cstdint>
#include <vector>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/cloud/radix_sort.hpp"
#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::segment {

struct RegionConfig {
  std::uint32_t k = 30;        // neighbours examined around each seed
  float angle_deg = 15.0f;     // max angle between neighbouring normals (stereo-noise tolerant)
  float curvature = 0.1f;      // points above this curvature join regions but do not seed them
  float distance = 0.02f;      // m; neighbours farther than this are not connected (0: no limit)
  std::uint32_t min_size = 50;        // smaller regions are dropped (or merged, with colour)
  std::uint32_t max_size = 10000000;  // larger regions are dropped
  bool smooth_mode = true;  // compare with the expanding point's normal (else the region seed's)
};

struct ColorConfig {
  bool enabled = false;
  float point_threshold = 6.0f;   // max RGB distance (0-255 units) between neighbouring points
  float region_threshold = 5.0f;  // max distance between the mean colours of merged regions
  float merge_distance = 0.02f;   // m; regions whose nearest points are closer may merge
};

struct Segmentation {
  std::vector<std::int32_t> label;  // per point: segment index or -1
  std::vector<std::vector<std::uint32_t>> segments;  // ascending point indices per segment
};

// Regions grow from the unlabelled point of lowest curvature. A neighbour joins the region when
// its normal is within angle_deg of the expanding point's (|n1.n2| >= cos angle), it lies within
// `distance`, and (with colour) its colour is within point_threshold; it expands the region
// further when its curvature is below `curvature`. Needs normals and curvature; with colour
// enabled, colours. Points with a NaN normal are left out. Deterministic and independent of the
// thread count. Throws Error for missing attributes.
Segmentation grow_regions(const Cloud& cloud, const RegionConfig& region,
                          const ColorConfig& color);
// The same with neighbour lists already computed for this cloud (nb.k >= region.k).
Segmentation grow_regions(const Cloud& cloud, const RegionConfig& region,
                          const ColorConfig& color, const cloud::Neighbours& nb);

// Its buffers, for a caller that segments a stream of frames (segment::Workspace).
struct RegionScratch {
  std::vector<std::uint64_t> seeds;  // the seed order's sort items
  std::vector<std::uint32_t> order, queue, size;
  std::vector<std::int32_t> renumber;
  cloud::RadixScratch sort;
  std::vector<std::vector<std::uint32_t>> spare;  // segment lists a frame with fewer left over
};
// The same into `out` (its lists' capacities reused, the segments' own too): without colour,
// a stream of frames asks the allocator for nothing once the buffers have grown to them.
void grow_regions(const Cloud& cloud, const RegionConfig& region, const ColorConfig& color,
                  const cloud::Neighbours& nb, Segmentation& out, RegionScratch& scratch);

}  // namespace uwgrasp::segment
