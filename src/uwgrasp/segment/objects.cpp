#include "uwgrasp/segment/objects.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>
#include <string>
#include <utility>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::segment {

namespace {
// The cells of side `cell` (a little over a part's reach) that hold a point of the part, over its
// box grown by a cell: a point none of whose 27 cells around holds one has no point of the part
// within reach, and the part's k-d tree is not built or asked for it (on the real stereo mug
// frame gathering the parts took 6.7 -> 1.2 ms; on mOSD_learn0, whose two objects stand 5-10 cm
// apart, 4.5 ms either way). Empty (every point may be near) when the grid would be too fine
// for the box.
class NearCells {
 public:
  NearCells(std::span<const Eigen::Vector3f> pts, const Eigen::AlignedBox3f& box, float reach)
      : cell_(1.01f * reach), lo_(box.min().array() - cell_) {
    if (!(reach > 0.0f) || box.isEmpty()) return;
    const Eigen::Array3f n = ((box.max().array() + cell_ - lo_) / cell_).floor() + 1.0f;
    if (n.prod() > float(1 << 22)) return;
    n_ = n.cast<int>();
    occupied_.assign(std::size_t(n_.prod()), 0);
    for (const auto& p : pts) occupied_[index(cell_of(p))] = 1;
  }
  bool may_reach(const Eigen::Vector3f& p) const {
    if (occupied_.empty()) return true;
    const Eigen::Array3i c = cell_of(p);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const Eigen::Array3i q = c + Eigen::Array3i(dx, dy, dz);
          if ((q >= 0).all() && (q < n_).all() && occupied_[index(q)]) return true;
        }
    return false;
  }

 private:
  Eigen::Array3i cell_of(const Eigen::Vector3f& p) const {
    // Clamped into [-1, n]: a point far outside the box lands next to it, never on a cell.
    const Eigen::Array3f f = ((p.array() - lo_) / cell_).floor();
    return f.max(-1.0f).min(n_.cast<float>()).cast<int>();
  }
  std::size_t index(const Eigen::Array3i& c) const {
    return std::size_t((c.z() * n_.y() + c.y()) * n_.x() + c.x());
  }
  float cell_;
  Eigen::Array3f lo_;
  Eigen::Array3i n_ = Eigen::Array3i::Zero();
  std::vector<char> occupied_;
};

Eigen::Vector3f centroid_of(const Cloud& cloud, const std::vector<std::uint32_t>& idx) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto i : idx) sum += cloud.points[i].cast<double>();
  return (sum / double(std::max<std::size_t>(idx.size(), 1))).cast<float>();
}

// The intensity a point must reach to count as of the colour: min_intensity, or, where the water
// dims every point below it, half of what the most coloured object's brighter points reach (the
// 90th percentile of its points' intensities) when that object stands out: at least 0.05, and
// twice every object farther than part_reach from it (nearer ones may be its own parts). In
// turbid water a red hot stab's points reach 0.12 and the seafloor's 0.05 at most; a scene with
// no object of the colour (a sandy seafloor's fragments alike) gets no threshold.
float colour_threshold(const Cloud& cloud, const Objects& o, const ObjectConfig& cfg) {
  std::vector<float> p90(o.points.size(), 0.0f), v;
  std::vector<Eigen::AlignedBox3f> box(o.points.size());
  for (std::size_t k = 0; k < o.points.size(); ++k) {
    v.clear();
    for (const auto i : o.points[k]) v.push_back(color_intensity(cloud.colors[i], cfg.color)), box[k].extend(cloud.points[i]);
    if (v.empty()) continue;
    if (*std::max_element(v.begin(), v.end()) >= cfg.min_intensity) return cfg.min_intensity;
    const auto at = v.begin() + std::ptrdiff_t(9 * v.size() / 10);
    std::nth_element(v.begin(), at, v.end());
    p90[k] = *at;
  }
  if (p90.empty()) return cfg.min_intensity;
  const std::size_t best = std::size_t(std::max_element(p90.begin(), p90.end()) - p90.begin());
  if (p90[best] < 0.05f) return cfg.min_intensity;
  for (std::size_t k = 0; k < o.points.size(); ++k)
    if (k != best && box[k].exteriorDistance(box[best]) > cfg.part_reach && 2.0f * p90[k] > p90[best])
      return cfg.min_intensity;
  return 0.5f * p90[best];
}

// Per object, its points of the colour (at the threshold) and their summed intensity.
struct Coloured {
  float threshold;
  std::vector<std::size_t> count;
  std::vector<double> intensity;
  std::size_t most() const {
    return count.empty() ? 0 : *std::max_element(count.begin(), count.end());
  }
};
Coloured coloured_points(const Cloud& cloud, const Objects& o, const ObjectConfig& cfg) {
  Coloured c{cloud.has_colors() ? colour_threshold(cloud, o, cfg) : cfg.min_intensity,
             std::vector<std::size_t>(o.points.size(), 0),
             std::vector<double>(o.points.size(), 0.0)};
  for (std::size_t k = 0; k < o.points.size(); ++k)
    for (const auto i : o.points[k])
      if (cloud.has_colors()) {
        const float v = color_intensity(cloud.colors[i], cfg.color);
        if (v >= c.threshold) ++c.count[k], c.intensity[k] += v;
      }
  return c;
}

// Colour mode: the object whose coloured points are the most intense, among the objects with at
// least a quarter of the most coloured one's coloured points.
std::size_t by_colour(const Cloud& cloud, const Objects& o, const ObjectConfig& cfg) {
  Coloured c = coloured_points(cloud, o, cfg);
  const std::size_t most = c.most();
  if (most == 0) {
    // Water takes red first, and more with range: say how to get the colour back, or do without.
    char value[32];
    std::snprintf(value, sizeof value, "%g", double(c.threshold));
    throw Error("no " + cfg.color + " object: none of " + std::to_string(o.points.size()) +
                " objects has a point of intensity >= " + value +
                " (segment.object.min_intensity); if water has faded it, preprocess.water.enabled restores "
                "colours, or select the object by point, nearest or largest");
  }
  std::size_t best = o.points.size();
  for (std::size_t k = 0; k < o.points.size(); ++k) {
    if (4 * c.count[k] < most) continue;
    c.intensity[k] /= double(c.count[k]);
    if (best == o.points.size() || c.intensity[k] > c.intensity[best]) best = k;
  }
  return best;
}
}  // namespace

bool has_colour_object(const Cloud& cloud, const Objects& objects, const ObjectConfig& cfg) {
  return !objects.points.empty() && coloured_points(cloud, objects, cfg).most() > 0;
}

std::size_t select_whole_object(const Cloud& cloud, const Objects& o, const Segmentation& seg,
                                const ObjectConfig& cfg) {
  if (o.points.empty()) throw Error("no objects: nothing to select as the object of interest");
  std::vector<char> wide(o.points.size(), 1);
  for (std::size_t k = 0; k < o.points.size() && geometric(cfg); ++k)
    wide[k] = !fragment(extent_of(cloud, o.points[k]), cfg);
  const std::size_t first = std::size_t(std::find(wide.begin(), wide.end(), 1) - wide.begin());
  if (first == wide.size()) throw_only_fragments(o.points.size(), "objects", cfg);
  const auto best = [&](auto key) {
    std::size_t b = first;
    for (std::size_t k = first + 1; k < o.points.size(); ++k)
      if (wide[k] && key(k) < key(b)) b = k;
    return b;
  };
  switch (cfg.by) {
    case ObjectBy::color: return by_colour(cloud, o, cfg);
    case ObjectBy::largest: return best([&](std::size_t k) { return -double(o.points[k].size()); });
    case ObjectBy::nearest:
      return best([&](std::size_t k) { return double((centroid_of(cloud, o.points[k]) - cloud.viewpoint).norm()); });
    case ObjectBy::label: {
      if (cfg.label >= seg.segments.size())
        throw Error("object label:" + std::to_string(cfg.label) + " does not exist (" +
                    std::to_string(seg.segments.size()) + " segments)");
      std::vector<std::size_t> votes(o.points.size(), 0);
      for (const auto i : seg.segments[cfg.label])
        if (o.object_of_point[i] >= 0) ++votes[std::size_t(o.object_of_point[i])];
      return best([&](std::size_t k) { return -double(votes[k]); });
    }
    case ObjectBy::point: {
      const Eigen::Vector3f p = cfg.point.cast<float>();
      std::size_t nearest = first;
      float d = std::numeric_limits<float>::max();
      for (std::size_t k = first; k < o.points.size(); ++k)
        for (const auto i : o.points[k])
          if (wide[k] && (cloud.points[i] - p).squaredNorm() < d)
            d = (cloud.points[i] - p).squaredNorm(), nearest = k;
      return nearest;
    }
  }
  throw Error("unknown object selection mode");
}

namespace {
// Which objects may join the selected one as its parts.
std::vector<char> eligible_parts(const Cloud& cloud, const Objects& o, std::size_t selected,
                                 const ObjectConfig& cfg) {
  std::vector<char> eligible(o.points.size(), 1);
  if (cfg.by == ObjectBy::color && cloud.has_colors()) {
    // A part: mostly (half its points) over min_intensity, or, as the water dims every part
    // alike, of a mean intensity at least half the selected object's. The first alone held in
    // clear water only: in turbid water a third of a red barbell's points, and a fifth of a
    // torque tool's, stay over min_intensity, and the parts the selected one needs were left
    // apart (no grasp); the second alone leaves shaded parts behind in clear water.
    std::vector<double> mean(o.points.size(), 0.0);
    std::vector<std::size_t> coloured(o.points.size(), 0);
    for (std::size_t k = 0; k < o.points.size(); ++k) {
      for (const auto i : o.points[k]) {
        const float v = color_intensity(cloud.colors[i], cfg.color);
        mean[k] += v, coloured[k] += v >= cfg.min_intensity;
      }
      mean[k] /= double(std::max<std::size_t>(1, o.points[k].size()));
    }
    for (std::size_t k = 0; k < o.points.size(); ++k)
      eligible[k] = 2 * coloured[k] >= o.points[k].size() || (mean[k] > 0.0 && 2.0 * mean[k] >= mean[selected]);
  } else if (cfg.by == ObjectBy::color) {
    std::fill(eligible.begin(), eligible.end(), 0);
  } else {  // no speck of snow joins the object as its part
    for (std::size_t k = 0; k < o.points.size(); ++k)
      eligible[k] = !fragment(extent_of(cloud, o.points[k]), cfg);
  }
  return eligible;
}
}  // namespace

std::vector<std::size_t> gather_parts(const Cloud& cloud, const Objects& o, std::size_t selected,
                                      const ObjectConfig& cfg, float reach) {
  std::vector<std::size_t> out{selected};
  std::vector<char> taken(o.points.size(), 0);
  taken[selected] = 1;
  const std::vector<char> eligible = eligible_parts(cloud, o, selected, cfg);
  // Each object's bounds: an object whose box lies beyond `reach` of a part's box has no point
  // within reach of it, and is not searched (on a real frame, most of the scene). The 0.1 %
  // allowance keeps a pair at exactly `reach` searched whatever the rounding of either distance.
  std::vector<Eigen::AlignedBox3f> box(o.points.size());
  for (std::size_t k = 0; k < o.points.size(); ++k)
    for (const auto i : o.points[k]) box[k].extend(cloud.points[i]);
  for (std::size_t next = 0; next < out.size(); ++next) {
    std::vector<Eigen::Vector3f> pts;
    for (const auto i : o.points[out[next]]) pts.push_back(cloud.points[i]);
    const NearCells near(pts, box[out[next]], reach);
    // The other objects' points that may reach the part, each object's in a run of `queries`.
    std::vector<std::pair<std::size_t, std::size_t>> runs;  // (object, end of its run)
    std::vector<Eigen::Vector3f> queries;
    Eigen::AlignedBox3f around;
    for (std::size_t k = 0; k < o.points.size(); ++k) {
      if (taken[k] || !eligible[k] || box[k].exteriorDistance(box[out[next]]) > 1.001f * reach + 1e-6f)
        continue;
      const std::size_t before = queries.size();
      for (const auto i : o.points[k])
        if (near.may_reach(cloud.points[i]))
          queries.push_back(cloud.points[i]), around.extend(cloud.points[i]);
      if (queries.size() > before) runs.emplace_back(k, queries.size());
    }
    if (runs.empty()) continue;
    // Only the part's points with a query within a cell of them can be within reach of one: the
    // tree holds those alone (on mOSD_learn0, 8,311 of the part's 20,257 points for 4,889 queries),
    // and any_within stops at the first point within reach (knn(q, 1) searched for the nearest).
    const NearCells back(queries, around, reach);
    std::erase_if(pts, [&](const Eigen::Vector3f& p) { return !back.may_reach(p); });
    if (pts.empty()) continue;
    const cloud::KdTree tree(pts);
    std::size_t from = 0;
    for (const auto& [k, end] : runs) {
      for (std::size_t j = from; j < end; ++j)
        if (tree.any_within(queries[j], reach)) {
          taken[k] = 1, out.push_back(k);
          break;
        }
      from = end;
    }
  }
  return out;
}

}  // namespace uwgrasp::segment
