#include "uwgrasp/cloud/filters.hpp"

#include <algorithm>
#include <utility>

#include "uwgrasp/cloud/indices.hpp"

namespace uwgrasp::cloud {

namespace {
// The cloud of the kept points; copied whole when nothing was dropped.
Filtered filtered(const Cloud& in, std::vector<std::uint32_t> indices) {
  Filtered out;
  out.indices = std::move(indices);
  if (out.indices.size() == in.size()) {
    out.cloud = in;
    make_unorganised(out.cloud);
  } else {
    out.cloud = select(in, out.indices);
  }
  return out;
}
}  // namespace

Filtered keep_if(const Cloud& in, const std::vector<char>& mask) {
  return filtered(in, indices_where(in.size(), [&](std::size_t i) { return mask[i] != 0; }));
}

Filtered remove_invalid(const Cloud& in) {
  return filtered(in, indices_where(in.size(), [&](std::size_t i) { return is_finite(in.points[i]); }));
}

std::vector<std::uint32_t> in_range(const Cloud& in, const RangeConfig& cfg) {
  const float lo2 = cfg.min * cfg.min, hi2 = cfg.max * cfg.max;
  return indices_where(in.size(), [&](std::size_t i) {
    const float d2 = (in.points[i] - in.viewpoint).squaredNorm();
    return is_finite(in.points[i]) & (d2 >= lo2) & (d2 <= hi2);
  });
}

Filtered crop_range(const Cloud& in, const RangeConfig& cfg) { return filtered(in, in_range(in, cfg)); }

}  // namespace uwgrasp::cloud
