#include "uwgrasp/cloud/filters.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace uwgrasp::cloud {

Filtered keep_if(const Cloud& in, const std::vector<char>& mask) {
  Filtered out;
  out.indices.reserve(in.size());
  for (std::size_t i = 0; i < in.size(); ++i)
    if (mask[i]) out.indices.push_back(static_cast<std::uint32_t>(i));
  out.cloud = select(in, out.indices);
  return out;
}

Filtered remove_invalid(const Cloud& in) {
  std::vector<char> mask(in.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.size(), 1 << 14), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) mask[i] = is_finite(in.points[i]);
  });
  return keep_if(in, mask);
}

Filtered crop_range(const Cloud& in, const RangeConfig& cfg) {
  std::vector<char> mask(in.size());
  const float lo2 = cfg.min * cfg.min, hi2 = cfg.max * cfg.max;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.size(), 1 << 14), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const float d2 = (in.points[i] - in.viewpoint).squaredNorm();
      mask[i] = is_finite(in.points[i]) && d2 >= lo2 && d2 <= hi2;
    }
  });
  return keep_if(in, mask);
}

}  // namespace uwgrasp::cloud
