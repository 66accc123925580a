// The objects of a processed cloud as the connected components of its neighbour lists, and the
// gap that joins them (objects.hpp).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/segment/objects.hpp"

namespace uwgrasp::segment {

namespace {
// A concurrent union-find: a root is linked under a smaller one by compare-and-swap, so along
// any path the indices fall (no cycles), and a find halves its path (a point's parent is only
// ever moved to one of its ancestors). Which points end up together does not depend on the
// order of the joins.
std::uint32_t find(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (true) {
    std::atomic_ref<std::uint32_t> up(parent[i]);
    const std::uint32_t p = up.load(std::memory_order_relaxed);
    if (p == i) return i;
    const std::uint32_t gp = std::atomic_ref<std::uint32_t>(parent[p]).load(std::memory_order_relaxed);
    if (gp != p) up.store(gp, std::memory_order_relaxed);
    i = gp;
  }
}

void unite(std::vector<std::uint32_t>& parent, std::uint32_t a, std::uint32_t b) {
  while (true) {
    a = find(parent, a), b = find(parent, b);
    if (a == b) return;
    if (a < b) std::swap(a, b);
    std::uint32_t expected = a;  // a is still a root, or another join got there first: again
    if (std::atomic_ref<std::uint32_t>(parent[a]).compare_exchange_strong(expected, b, std::memory_order_relaxed)) return;
  }
}
}  // namespace

Objects connected_objects(const Cloud& cloud, const cloud::Neighbours& nb, float gap,
                          std::uint32_t min_points) {
  const std::size_t n = cloud.size();
  if (nb.count.size() != n) throw Error("connected objects: neighbour lists do not match the cloud");
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  const float g2 = gap * gap;
  // The points' joins in parallel (serially 6 ms on the real stereo mug frame); a window list's
  // pair is joined once, from its lower index (the lists are symmetric).
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 2048), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const auto idx = nb.of(i);
      const auto d2 = nb.dists_of(i);
      for (std::size_t k = 0; k < idx.size(); ++k)
        if (d2[k] <= g2 && (!nb.window || idx[k] > i)) unite(parent, std::uint32_t(i), idx[k]);
    }
  });
  std::vector<std::uint32_t> root(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) { root[i] = find(parent, std::uint32_t(i)); });
  std::vector<std::uint32_t> size(n, 0);
  for (std::size_t i = 0; i < n; ++i) ++size[root[i]];
  // Objects numbered by their lowest point index: the same output whatever the order of joins.
  Objects out;
  out.object_of_point.assign(n, -1);
  std::vector<std::int32_t> number(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t r = root[i];
    if (size[r] < min_points) continue;
    if (number[r] < 0) number[r] = std::int32_t(out.points.size()), out.points.emplace_back();
    out.object_of_point[i] = number[r];
    out.points[std::size_t(number[r])].push_back(std::uint32_t(i));
  }
  return out;
}

float connection_gap(const cloud::Neighbours& nb, float spacing_mul, float lo, float hi) {
  std::vector<float> d;
  for (std::size_t i = 0; i < nb.count.size(); i += 7) {  // a sample is plenty for a median
    float nearest = std::numeric_limits<float>::infinity();  // window lists are not sorted
    for (const float d2 : nb.dists_of(i))
      if (d2 > 0.0f) nearest = std::min(nearest, d2);
    if (std::isfinite(nearest)) d.push_back(std::sqrt(nearest));
  }
  if (d.empty()) return lo;
  std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(d.size() / 2), d.end());
  return std::clamp(spacing_mul * d[d.size() / 2], lo, hi);
}

}  // namespace uwgrasp::segment
