#include "uwgrasp/grasp/symmetry.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "uwgrasp/cloud/kdtree.hpp"

namespace uwgrasp::grasp {

namespace {
using V3 = Eigen::Vector3f;

V3 direction(float azimuth, float tilt) {
  return {std::cos(azimuth) * std::cos(tilt), std::sin(azimuth) * std::cos(tilt), std::sin(tilt)};
}

struct Scored {
  MirrorPlane plane;
  bool valid = false;
};

// The best offset for normal n over [lo, hi] every `step`: mirrored about n.p = d, point i lands
// at level_i + d w in L and base_i + d u in the camera frame (level_i = p_i - 2 s_i n, w = 2 n,
// base_i = T_CL level_i, u = R_CL w). Where the
// best score holds over a run of offsets (the tolerance lets a plane slide a little), the middle
// of the run: its first offset would bias every plane towards the camera.
Scored best_offset(std::span<const V3> sample, const V3& n, const SceneView& view, float lo, float hi,
                   float step, float tolerance, const SymmetryConfig& cfg) {
  const Eigen::Matrix3f R = view.camera_from_level.linear().cast<float>();
  const V3 t = view.camera_from_level.translation().cast<float>();
  std::vector<V3> base(sample.size()), level(sample.size());
  for (std::size_t i = 0; i < sample.size(); ++i) {
    level[i] = sample[i] - 2.0f * n.dot(sample[i]) * n;
    base[i] = R * level[i] + t;
  }
  const V3 u = 2.0f * (R * n), w = 2.0f * n;
  const float size = float(sample.size());
  const int limit = int(std::floor(cfg.max_violations * size));
  std::vector<MirrorPlane> tried;
  for (int k = 0; lo + float(k) * step <= hi + 1e-6f; ++k) {
    const float d = lo + float(k) * step;
    int support = 0, violations = 0;
    for (std::size_t i = 0; i < base.size() && violations <= limit; ++i) {
      const Seen s = classify_camera(view, base[i] + d * u, level[i] + d * w, tolerance);
      support += s == Seen::support, violations += s == Seen::violation;
    }
    // Past the violation limit the plane cannot be kept: the rest of the sample is not asked.
    const float score = violations > limit ? -std::numeric_limits<float>::infinity()
                                           : (float(support) - cfg.violation_weight * float(violations)) / size;
    tried.push_back({n, d, float(support) / size, float(violations) / size, score});
  }
  std::size_t best = 0;
  for (std::size_t k = 1; k < tried.size(); ++k)
    if (tried[k].score > tried[best].score) best = k;
  if (tried.empty() || !std::isfinite(tried[best].score)) return {};
  const float near_best = tried[best].score - 1.0f / size;  // within one point of the best
  std::size_t first = best, last = best;
  while (first > 0 && tried[first - 1].score >= near_best) --first;
  while (last + 1 < tried.size() && tried[last + 1].score >= near_best) ++last;
  return {tried[(first + last) / 2], true};
}

struct Search {
  std::span<const V3> sample, coarse_sample;  // the coarse grid scores a third of the sample
  const SceneView& view;
  float tolerance;
  const SymmetryConfig& cfg;
  V3 centroid;

  Scored coarse(const V3& n) const {
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (const V3& p : sample) lo = std::min(lo, n.dot(p)), hi = std::max(hi, n.dot(p));
    // The plane lies inside the object, whose unseen part may reach past the seen one.
    const float reach = std::max(0.02f, 0.5f * (hi - lo));
    return best_offset(coarse_sample, n, view, lo, hi + reach, cfg.offset_step, tolerance, cfg);
  }
  // Finer normals and offsets around a coarse plane.
  // The normals are scored in parallel, then taken in their order (the first of equal scores).
  Scored refine(const Scored& c, float azimuth, float tilt, float tilt_step) const {
    const float da = 0.25f * cfg.angle_step, dt = 0.25f * tilt_step, dd = 0.25f * cfg.offset_step;
    const int tilt_steps = dt > 0.0f ? 3 : 0, columns = 2 * tilt_steps + 1;
    std::vector<Scored> tried(std::size_t(7 * columns));
    tbb::parallel_for(std::size_t(0), tried.size(), [&](std::size_t k) {
      const int i = int(k) / columns - 3, j = int(k) % columns - tilt_steps;
      const float tl = std::clamp(tilt + float(j) * dt, -cfg.max_tilt, cfg.max_tilt);
      const V3 n = direction(azimuth + float(i) * da, tl);
      // The same plane turned about the point of it nearest the sample's centroid.
      const float d0 = n.dot(c.plane.mirror(centroid) + (c.plane.normal.dot(centroid) - c.plane.offset) * c.plane.normal);
      tried[k] = best_offset(sample, n, view, d0 - 4.0f * dd, d0 + 4.0f * dd, dd, tolerance, cfg);
    });
    Scored best;
    for (const Scored& s : tried)
      if (s.valid && (!best.valid || s.plane.score > best.plane.score)) best = s;
    return best;
  }
};

// Aligns a plane to the point pairs it maps onto each other: a seen point p whose mirror lands on
// the seen surface near q makes (p, q) a mirror pair, whose difference lies along the normal and
// whose midpoint lies on the plane. The normal is the principal direction of the differences
// (weighted by their squared length: far pairs fix it best), the offset the midpoints' mean.
// The grid search alone leaves the normal a few degrees off - a box's mirrored face would tilt
// by twice that, and friction predicted on it with it.
MirrorPlane align(MirrorPlane plane, std::span<const V3> sample, const cloud::KdTree& seen,
                  const SceneView& view, float tolerance) {
  for (int iteration = 0; iteration < 3; ++iteration) {
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    Eigen::Vector3d middle = Eigen::Vector3d::Zero();
    double weight = 0.0;
    std::size_t pairs = 0;
    for (const V3& p : sample) {
      const V3 m = plane.mirror(p);
      if (classify(view, m, tolerance) != Seen::support) continue;
      std::uint32_t index = 0;
      float d2 = 0.0f;
      if (seen.knn(m, 1, &index, &d2) == 0 || d2 > 4.0f * tolerance * tolerance) continue;
      const V3 q = seen.points()[index];
      const Eigen::Vector3d diff = (p - q).cast<double>();
      if (diff.norm() < 4.0 * tolerance) continue;  // too near the plane to tell its direction
      const double w = diff.squaredNorm();
      scatter += diff * diff.transpose();
      middle += w * (0.5f * (p + q)).cast<double>();
      weight += w, ++pairs;
    }
    if (pairs < 10) return plane;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(scatter);
    V3 n = es.eigenvectors().col(2).cast<float>().normalized();
    if (n.dot(plane.normal) < 0.0f) n = -n;
    if (n.dot(plane.normal) < std::cos(0.2f)) return plane;  // the pairs disagree with the plane
    plane.normal = n;
    plane.offset = n.dot((middle / weight).cast<float>());
  }
  return plane;
}

bool acceptable(const MirrorPlane& p, const SymmetryConfig& cfg) {
  return p.score > 0.0f && p.violations <= cfg.max_violations && p.support >= cfg.min_support;
}
}  // namespace

std::vector<MirrorPlane> find_symmetry(std::span<const Eigen::Vector3f> level, const SceneView& view,
                                       float noise, const SymmetryConfig& cfg) {
  if (!cfg.enabled || level.size() < 10 || !(cfg.angle_step > 0.0f) || !(cfg.offset_step > 0.0f)) return {};
  std::vector<V3> sample;
  const std::size_t stride = std::max<std::size_t>(1, level.size() / std::max<std::uint32_t>(cfg.samples, 1));
  for (std::size_t i = 0; i < level.size(); i += stride) sample.push_back(level[i]);
  V3 centroid = V3::Zero();
  for (const V3& p : sample) centroid += p;
  std::vector<V3> coarse_sample;
  for (std::size_t i = 0; i < sample.size(); i += 3) coarse_sample.push_back(sample[i]);
  const Search search{sample, coarse_sample, view, cfg.tolerance + cfg.noise_sigmas * noise, cfg, centroid / float(sample.size())};
  // Azimuths over half a turn: n and -n are one plane family, the tilt's sign covers the rest.
  const int azimuths = std::max(1, int(std::lround(std::numbers::pi_v<float> / cfg.angle_step)));
  const float tilt_step = 2.0f * cfg.angle_step;
  const int tilts = cfg.max_tilt > 0.0f ? int(std::floor(cfg.max_tilt / tilt_step)) : 0;
  const int rows = 2 * tilts + 1;
  std::vector<Scored> coarse(std::size_t(azimuths) * std::size_t(rows));
  tbb::parallel_for(std::size_t(0), coarse.size(), [&](std::size_t k) {
    const float a = float(k % std::size_t(azimuths)) * cfg.angle_step;
    const float t = float(int(k / std::size_t(azimuths)) - tilts) * tilt_step;
    coarse[k] = search.coarse(direction(a, t));
  });
  // The best plane `allowed` lets through, refined; a tilted plane must beat the best upright
  // one by tilt_margin (objects rest on the seafloor: upright symmetry is the likelier one, and
  // noise alone makes a small tilt score a little higher).
  const auto best_where = [&](auto&& allowed) {
    std::size_t best = coarse.size(), upright = coarse.size();
    for (std::size_t k = 0; k < coarse.size(); ++k) {
      if (!coarse[k].valid || !allowed(coarse[k].plane)) continue;
      if (best == coarse.size() || coarse[k].plane.score > coarse[best].plane.score) best = k;
      const bool flat = int(k / std::size_t(azimuths)) == tilts;
      if (flat && (upright == coarse.size() || coarse[k].plane.score > coarse[upright].plane.score)) upright = k;
    }
    if (best == coarse.size()) return Scored{};
    const auto refined = [&](std::size_t k, float tilt_range) {
      const float a = float(k % std::size_t(azimuths)) * cfg.angle_step;
      const float t = float(int(k / std::size_t(azimuths)) - tilts) * tilt_step;
      return search.refine(coarse[k], a, t, tilt_range);
    };
    const Scored upright_best = upright == coarse.size() ? Scored{} : refined(upright, 0.0f);
    if (best == upright) return upright_best;
    const Scored tilted = refined(best, tilt_step);
    return upright_best.valid && tilted.plane.score < upright_best.plane.score + cfg.tilt_margin ? upright_best : tilted;
  };
  // Each plane aligned to the mirror pairs it makes, kept aligned unless that scores worse.
  const cloud::KdTree tree(level);
  const auto aligned = [&](const Scored& s) {
    if (!s.valid) return s;
    const MirrorPlane a = align(s.plane, sample, tree, view, search.tolerance);
    // The offset searched again along the aligned normal: the midpoints of pairs found through
    // a plane a little off are a little off too.
    const float step = 0.25f * cfg.offset_step;
    const Scored t = best_offset(sample, a.normal, view, a.offset - 8.0f * step, a.offset + 8.0f * step, step,
                                 search.tolerance, cfg);
    return t.valid && t.plane.score >= s.plane.score - 0.02f ? t : s;
  };
  std::vector<MirrorPlane> planes;
  const Scored first = aligned(best_where([](const MirrorPlane&) { return true; }));
  if (!first.valid || !acceptable(first.plane, cfg)) return planes;
  planes.push_back(first.plane);
  const float cos70 = std::cos(70.0f * std::numbers::pi_v<float> / 180.0f);
  const Scored second = aligned(best_where(
      [&](const MirrorPlane& p) { return std::abs(p.normal.dot(first.plane.normal)) < cos70; }));
  if (second.valid && acceptable(second.plane, cfg)) planes.push_back(second.plane);
  return planes;
}

void mirror_points(std::span<const Eigen::Vector3f> level, std::span<const Eigen::Vector3f> normals,
                   std::span<const MirrorPlane> planes, const SceneView& view, float tolerance,
                   std::vector<Eigen::Vector3f>& points, std::vector<Eigen::Vector3f>& out_normals) {
  const auto keep = [&](const V3& p, const V3& n) {
    if (classify(view, p, tolerance) == Seen::hidden) points.push_back(p), out_normals.push_back(n);
  };
  for (std::size_t i = 0; i < level.size(); ++i) {
    const V3 n = i < normals.size() ? normals[i] : V3::Zero();
    for (std::size_t a = 0; a < planes.size(); ++a) {
      const V3 p = planes[a].mirror(level[i]), m = planes[a].mirror_direction(n);
      keep(p, m);
      for (std::size_t b = a + 1; b < planes.size(); ++b) keep(planes[b].mirror(p), planes[b].mirror_direction(m));
    }
  }
}

}  // namespace uwgrasp::grasp
