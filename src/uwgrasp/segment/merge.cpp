#include "uwgrasp/segment/merge.hpp"

#include <algorithm>
#include <limits>
#include <tuple>

namespace uwgrasp::segment {

namespace {
struct Link {
  std::uint32_t other;
  float sq_dist;  // between the closest neighbouring points of the two regions
};

// For every region, its neighbouring regions (linked through the points' kNN lists) sorted by
// distance, then id.
std::vector<std::vector<Link>> region_links(const cloud::Neighbours& nb,
                                            const std::vector<std::int32_t>& labels,
                                            std::uint32_t count) {
  std::vector<std::tuple<std::uint32_t, std::uint32_t, float>> pairs;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] < 0) continue;
    const auto idx = nb.of(i);
    const auto d2 = nb.dists_of(i);
    for (std::size_t j = 0; j < idx.size(); ++j) {
      const auto l = labels[idx[j]];
      if (l >= 0 && l != labels[i])
        pairs.emplace_back(static_cast<std::uint32_t>(labels[i]), static_cast<std::uint32_t>(l),
                           d2[j]);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::vector<Link>> links(count);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto [a, b, d] = pairs[i];
    if (i > 0 && std::get<0>(pairs[i - 1]) == a && std::get<1>(pairs[i - 1]) == b) continue;
    links[a].push_back({b, d});  // first of each (a, b) run holds the minimum distance
  }
  for (auto& l : links)
    std::sort(l.begin(), l.end(), [](const Link& x, const Link& y) {
      return std::tie(x.sq_dist, x.other) < std::tie(y.sq_dist, y.other);
    });
  return links;
}

std::vector<Eigen::Vector3d> mean_colors(const Cloud& c, const std::vector<std::int32_t>& labels,
                                         std::uint32_t count, std::vector<std::uint32_t>& size) {
  std::vector<Eigen::Vector3d> sum(count, Eigen::Vector3d::Zero());
  size.assign(count, 0);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] < 0) continue;
    const auto l = static_cast<std::size_t>(labels[i]);
    sum[l] += Eigen::Vector3d(c.colors[i].r, c.colors[i].g, c.colors[i].b);
    ++size[l];
  }
  for (std::uint32_t s = 0; s < count; ++s)
    if (size[s] > 0) sum[s] /= size[s];
  return sum;
}
}  // namespace

std::uint32_t merge_regions(const Cloud& cloud, const cloud::Neighbours& nb,
                            std::vector<std::int32_t>& labels, std::uint32_t count,
                            const RegionConfig& region, const ColorConfig& color) {
  std::vector<std::uint32_t> size;
  const auto mean = mean_colors(cloud, labels, count, size);
  const auto links = region_links(nb, labels, count);
  const float merge2 = color.merge_distance * color.merge_distance;

  // 1. Homogeneous merging: in region order, unassigned neighbours within merge_distance whose
  //    mean colour is within region_threshold join the current region's group.
  std::vector<std::int32_t> group(count, -1);
  std::vector<std::vector<std::uint32_t>> members;
  for (std::uint32_t s = 0; s < count; ++s) {
    if (group[s] == -1) group[s] = static_cast<std::int32_t>(members.size()), members.emplace_back();
    const auto g = group[s];
    members[static_cast<std::size_t>(g)].push_back(s);
    for (const Link& l : links[s]) {
      if (l.sq_dist > merge2 || group[l.other] != -1) continue;
      if ((mean[s] - mean[l.other]).norm() < color.region_threshold) group[l.other] = g;
    }
  }
  // 2. Groups below min_size merge into their nearest neighbouring group, in group order.
  std::vector<std::uint32_t> gsize(members.size(), 0);
  for (std::uint32_t s = 0; s < count; ++s) gsize[static_cast<std::size_t>(group[s])] += size[s];
  for (std::size_t g = 0; g < members.size(); ++g) {
    if (members[g].empty() || gsize[g] >= region.min_size) continue;
    float best = std::numeric_limits<float>::infinity();
    std::int32_t to = -1;
    for (auto s : members[g])
      for (const Link& l : links[s]) {
        const auto og = group[l.other];
        if (og != static_cast<std::int32_t>(g) && (l.sq_dist < best || (l.sq_dist == best && og < to)))
          best = l.sq_dist, to = og;
      }
    if (to < 0) continue;
    auto& dst = members[static_cast<std::size_t>(to)];
    for (auto s : members[g]) group[s] = to, dst.push_back(s);
    gsize[static_cast<std::size_t>(to)] += gsize[g];
    members[g].clear();
    gsize[g] = 0;
  }
  // Dense numbering of the surviving groups in order of their lowest region.
  std::vector<std::int32_t> dense(members.size(), -1);
  std::int32_t next = 0;
  for (std::uint32_t s = 0; s < count; ++s) {
    auto& d = dense[static_cast<std::size_t>(group[s])];
    if (d == -1) d = next++;
  }
  for (auto& l : labels)
    if (l >= 0) l = dense[static_cast<std::size_t>(group[static_cast<std::size_t>(l)])];
  return static_cast<std::uint32_t>(next);
}

}  // namespace uwgrasp::segment
