#include "uwgrasp/cloud/filters.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <utility>

namespace uwgrasp::cloud {

namespace {
constexpr std::size_t kChunk = std::size_t(1) << 14;

// The indices i < n with keep(i), ascending. Fixed chunks count them in parallel, then each
// writes its own from its offset (keep is evaluated twice instead of stored): the same list at
// any thread count.
template <class Keep>
std::vector<std::uint32_t> kept(std::size_t n, Keep keep) {
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  const auto end = [&](std::size_t c) { return std::min(n, (c + 1) * kChunk); };
  std::vector<std::size_t> start(chunks + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      std::size_t count = 0;
      for (std::size_t i = c * kChunk; i < end(c); ++i) count += keep(i) ? 1 : 0;
      start[c + 1] = count;
    }
  });
  for (std::size_t c = 0; c < chunks; ++c) start[c + 1] += start[c];
  std::vector<std::uint32_t> out(start[chunks]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      std::uint32_t* at = out.data() + start[c];
      for (std::size_t i = c * kChunk; i < end(c); ++i)
        if (keep(i)) *at++ = static_cast<std::uint32_t>(i);
    }
  });
  return out;
}

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
  return filtered(in, kept(in.size(), [&](std::size_t i) { return mask[i] != 0; }));
}

Filtered remove_invalid(const Cloud& in) {
  return filtered(in, kept(in.size(), [&](std::size_t i) { return is_finite(in.points[i]); }));
}

std::vector<std::uint32_t> in_range(const Cloud& in, const RangeConfig& cfg) {
  const float lo2 = cfg.min * cfg.min, hi2 = cfg.max * cfg.max;
  return kept(in.size(), [&](std::size_t i) {
    const float d2 = (in.points[i] - in.viewpoint).squaredNorm();
    return is_finite(in.points[i]) & (d2 >= lo2) & (d2 <= hi2);
  });
}

Filtered crop_range(const Cloud& in, const RangeConfig& cfg) { return filtered(in, in_range(in, cfg)); }

}  // namespace uwgrasp::cloud
