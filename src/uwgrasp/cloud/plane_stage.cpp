#include "uwgrasp/cloud/plane_stage.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <unordered_set>
#include <utility>

#include "uwgrasp/cloud/indices.hpp"

namespace uwgrasp::cloud {

namespace {
// Points behind a plane, as a share of its inliers, that are too few to make it an object's face.
constexpr double kFewBehind = 0.05;

// std::int64_t(std::floor(x)) without a library call where |x| is of a cell index's size
// (std::floor is one on x86-64 before SSE4.1; two per point, 300k points a frame).
std::int64_t floor_int(float x) {
  if (!(std::abs(x) < 0x1p62f)) return std::int64_t(std::floor(x));  // as before, elsewhere
  const auto t = std::int64_t(x);  // towards zero
  return t - std::int64_t(float(t) > x);
}

// The plane cells (u, v) holding an inlier, for supports_the_rest: a bitmap over the inliers'
// cells when it is small (a frame's floor: a few hundred thousand cells; an unordered_set of
// 200k inliers took 3 ms to fill), else a hash set.
class CellSet {
 public:
  // `cells` and `bits` are the caller's buffers (PlaneScratch), kept over a stream of frames.
  template <class UV>
  CellSet(const Cloud& cur, const std::vector<std::uint32_t>& inliers, UV uv,
          std::vector<std::pair<std::int64_t, std::int64_t>>& cells, std::vector<char>& bits)
      : bits_(bits) {
    cells.resize(inliers.size());
    tbb::parallel_for(std::size_t(0), inliers.size(), [&](std::size_t k) { cells[k] = uv(cur.points[inliers[k]]); });
    if (cells.empty()) return;
    lo_ = hi_ = cells.front();
    for (const auto& [u, v] : cells) lo_ = {std::min(lo_.first, u), std::min(lo_.second, v)}, hi_ = {std::max(hi_.first, u), std::max(hi_.second, v)};
    const double w = double(hi_.first - lo_.first) + 1.0, h = double(hi_.second - lo_.second) + 1.0;
    dense_ = w * h <= double(kMaxCells);
    if (dense_) {
      width_ = std::int64_t(w);
      bits_.assign(std::size_t(w * h), 0);
      for (const auto& c : cells) bits_[index(c)] = 1;
    } else {
      for (const auto& c : cells) set_.insert(key(c));
    }
  }
  // Whether (u, v) or one of its 8 neighbours holds an inlier.
  bool near(std::pair<std::int64_t, std::int64_t> c) const {
    for (std::int64_t du = -1; du <= 1; ++du)
      for (std::int64_t dv = -1; dv <= 1; ++dv)
        if (has({c.first + du, c.second + dv})) return true;
    return false;
  }

 private:
  static constexpr std::size_t kMaxCells = std::size_t(1) << 24;
  using Cell = std::pair<std::int64_t, std::int64_t>;
  static std::int64_t key(Cell c) { return (c.first << 32) ^ (c.second & 0xffffffff); }
  std::size_t index(Cell c) const { return std::size_t((c.second - lo_.second) * width_ + (c.first - lo_.first)); }
  bool has(Cell c) const {
    if (!dense_) return set_.count(key(c)) > 0;
    if (c.first < lo_.first || c.second < lo_.second || c.first > hi_.first || c.second > hi_.second) return false;
    return bits_[index(c)] != 0;
  }
  Cell lo_{0, 0}, hi_{-1, -1};
  std::int64_t width_ = 0;
  bool dense_ = true;
  std::vector<char>& bits_;
  std::unordered_set<std::int64_t> set_;
};
}  // namespace

// The plane's inliers again, within max(distance, noise_sigmas x sigma(range)) of it: the noise
// is measured twice, the second time in a band wide enough for the first estimate's spread.
void widen_to_noise(const Cloud& cur, const PlaneConfig& cfg, Preprocessed& out,
                    PlaneScratch& scratch) {
  // Each point's distance and range once, for both measurements and the band's test.
  NoiseScratch& noise = scratch.noise;
  plane_distances(cur, out.plane.coefficients, noise.point_distance, noise.point_range);
  const std::vector<float>&distance = noise.point_distance, &range = noise.point_range;
  float band = std::max(3.0f * cfg.distance, 0.02f);
  out.noise = plane_noise(distance, range, band, kNoiseBin, kNoiseMinPoints, noise);
  if (!out.noise.found) return;
  // The widest noise over the inliers: the farthest inlier's (sigma0, sigma_k >= 0, so sigma
  // never falls with range).
  const std::vector<std::uint32_t>& in = out.plane.inliers;
  const float farthest = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, in.size()), 0.0f,
      [&](const auto& r, float w) {
        for (std::size_t k = r.begin(); k != r.end(); ++k) w = std::max(w, range[in[k]]);
        return w;
      },
      [](float a, float b) { return std::max(a, b); });
  const float widest = in.empty() ? 0.0f : float(out.noise.at(farthest));
  if (5.0f * widest > band)
    out.noise = plane_noise(distance, range, 5.0f * widest, kNoiseBin, kNoiseMinPoints, noise);
  if (!out.noise.found) return;
  const auto inlier = [&](std::size_t i) {
    if (distance[i] <= cfg.distance) return true;  // within the fixed tolerance whatever the noise
    return distance[i] <= cfg.noise_sigmas * out.noise.at(range[i]);
  };
  indices_where(cur.size(), inlier, out.plane.inliers);
}

// Of the widened band's points beyond the fixed tolerance, those whose window normal turns more
// than normal_angle from the plane's leave the inliers (4.1.4 with the normals, as PCL's
// organised plane segmentation also tests them).
void keep_turned_points(const Cloud& cur, const PixelMap& map, const PreprocessConfig& cfg,
                        PlaneResult& plane, PlaneScratch& scratch, WindowScratch& window) {
  const Eigen::Vector4f& n = plane.coefficients;
  std::vector<std::uint32_t>& band = scratch.band;
  band.clear();
  for (const auto i : plane.inliers)
    if (std::abs(n.head<3>().dot(cur.points[i]) + n[3]) > cfg.plane.distance) band.push_back(i);
  if (band.empty()) return;
  std::vector<PointNormal>& normals = scratch.band_normals;
  window_normals_of(cur.points, map, cfg.organised, cur.viewpoint, band, normals, window);
  const float cos_max = std::cos(cfg.plane.normal_angle * float(std::numbers::pi) / 180.0f);
  std::vector<char>& off = scratch.off;
  off.assign(cur.size(), 0);
  for (std::size_t b = 0; b < band.size(); ++b)
    off[band[b]] = std::abs(normals[b].normal.dot(n.head<3>())) < cos_max;
  std::erase_if(plane.inliers, [&](std::uint32_t i) { return off[i] != 0; });
}

// Whether the points clearly off the plane (beyond three inlier distances) and over its inliers
// (their projection along the normal within a cell of an inlier's) lie mostly on the sensor's
// side of it, as objects standing on a support do, rather than behind it, as the rest of an
// object does behind one of its own faces. Points beyond the plane's edge (the room behind a
// table) do not count either way. Nor do a few behind it: an opaque support hides what is behind
// it, so those are mismatches (stereo's, a few hundred on a seafloor with only a pipe lying on
// it, which puts nothing in front), while an object's other faces are a sizeable share of it.
bool supports_the_rest(const Cloud& cur, const PlaneConfig& cfg, const PlaneResult& plane) {
  PlaneScratch scratch;
  return supports_the_rest(cur, cfg, plane, scratch);
}

bool supports_the_rest(const Cloud& cur, const PlaneConfig& cfg, const PlaneResult& plane,
                       PlaneScratch& scratch) {
  const Eigen::Vector4f& n = plane.coefficients;
  const Eigen::Vector3f normal = n.head<3>();
  const Eigen::Vector3f a = normal.unitOrthogonal(), b = normal.cross(a);
  const float cell = std::max(2.0f * cfg.distance, 0.01f);
  const auto uv = [&](const Eigen::Vector3f& p) {
    return std::pair(floor_int(a.dot(p) / cell), floor_int(b.dot(p) / cell));
  };
  const CellSet over(cur, plane.inliers, uv, scratch.cells, scratch.bits);
  const float sensor = normal.dot(cur.viewpoint) + n[3];
  using Tally = std::array<std::size_t, 2>;  // front, behind: integer sums, any order
  const Tally t = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, cur.size(), 4096), Tally{},
      [&](const auto& r, Tally c) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const Eigen::Vector3f& p = cur.points[i];
          const float d = normal.dot(p) + n[3];
          if (std::abs(d) <= 3.0f * cfg.distance || !over.near(uv(p))) continue;
          ++c[d * sensor > 0.0f ? 0 : 1];
        }
        return c;
      },
      [](Tally x, const Tally& y) { return Tally{x[0] + y[0], x[1] + y[1]}; });
  return t[0] >= t[1] || double(t[1]) < kFewBehind * double(plane.inliers.size());
}

}  // namespace uwgrasp::cloud
