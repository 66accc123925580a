#pragma once
// Invalid-value removal (thesis 4.1.1) and range crop (the 6 m sensor limit of 7.4.1).
#include <cstdint>
#include <vector>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::cloud {

// A filtered cloud and, for each of its points, the index of that point in the input. For an
// organised input the indices are pixel indices (row = i / width), so the layout stays available.
struct Filtered {
  Cloud cloud;
  std::vector<std::uint32_t> indices;
};

// Keeps points whose x, y and z are all finite (4.1.1).
Filtered remove_invalid(const Cloud& in);

struct RangeConfig {
  bool enabled = true;
  float min = 0.0f;  // m from the viewpoint
  float max = 6.0f;  // m; the thesis limits its depth sensor to 6 m (7.4.1)
};
// Keeps finite points whose distance from the viewpoint lies in [min, max].
Filtered crop_range(const Cloud& in, const RangeConfig& cfg);
// The indices crop_range keeps (ascending), without copying the cloud.
std::vector<std::uint32_t> in_range(const Cloud& in, const RangeConfig& cfg);

// Keeps the points whose mask entry is true (mask.size() == in.size()).
Filtered keep_if(const Cloud& in, const std::vector<char>& mask);

}  // namespace uwgrasp::cloud
