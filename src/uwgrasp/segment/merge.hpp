#pragma once
// Region merging of the RGB variant (thesis 4.2.2): neighbouring regions with close mean colours
// merge; regions still below the minimum size merge into their nearest neighbouring region.
#include <cstdint>
#include <vector>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/segment/region_growing.hpp"

namespace uwgrasp::segment {

// Rewrites `labels` (region per point, -1 none, regions 0..count-1) to merged region numbers and
// returns the new count.
std::uint32_t merge_regions(const Cloud& cloud, const cloud::Neighbours& nb,
                            std::vector<std::int32_t>& labels, std::uint32_t count,
                            const RegionConfig& region, const ColorConfig& color);

}  // namespace uwgrasp::segment
