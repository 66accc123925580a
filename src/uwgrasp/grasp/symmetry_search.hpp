#pragma once
// Internal to grasp/: the symmetry search's pieces (symmetry_search.cpp) that find_symmetry
// (symmetry.cpp) puts together - a plane's best offset, the grids of normals around it, and its
// alignment to the mirror pairs it makes.
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/grasp/symmetry.hpp"

namespace uwgrasp::grasp::symmetry_detail {
using V3 = Eigen::Vector3f;

inline V3 direction(float azimuth, float tilt) {
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
                   float step, float tolerance, const SymmetryConfig& cfg);

struct Search {
  std::span<const V3> sample, coarse_sample;  // the coarse grid scores a third of the sample
  const SceneView& view;
  float tolerance;
  const SymmetryConfig& cfg;
  V3 centroid;
  // The frame the normals' azimuth and tilt are taken in (z: the seafloor's down), in L; the
  // identity, and no turn made, on a level seafloor.
  Eigen::Matrix3f level_from_upright = Eigen::Matrix3f::Identity();
  bool sloped = false;

  V3 down() const { return level_from_upright.col(2); }
  // The normal at `azimuth` and `tilt` (from the seafloor's horizontal), in L.
  V3 normal_at(float azimuth, float tilt) const {
    const V3 n = direction(azimuth, tilt);
    return sloped ? V3(level_from_upright * n) : n;
  }

  Scored coarse(const V3& n) const {
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (const V3& p : sample) lo = std::min(lo, n.dot(p)), hi = std::max(hi, n.dot(p));
    // The plane lies inside the object, whose unseen part may reach past the seen one.
    const float reach = std::max(0.02f, 0.5f * (hi - lo));
    return best_offset(coarse_sample, n, view, lo, hi + reach, cfg.offset_step, tolerance, cfg);
  }
  // The best offset for normal n within four quarter offset steps of d0.
  Scored near(const V3& n, float d0) const {
    const float dd = 0.25f * cfg.offset_step;
    return best_offset(sample, n, view, d0 - 4.0f * dd, d0 + 4.0f * dd, dd, tolerance, cfg);
  }
  // Plane c turned to normal n about the point of it nearest the sample's centroid.
  Scored turned_to(const MirrorPlane& c, const V3& n) const {
    return near(n, n.dot(c.mirror(centroid) + (c.normal.dot(centroid) - c.offset) * c.normal));
  }
  // The planes whose normals are perpendicular to `axis` (a unit normal), turned by phi from the
  // horizontal one (the seafloor's): m = cos(phi) a + sin(phi) b, a = the horizontal unit vector
  // across the axis, b = axis x a (vertical when the axis is horizontal). Each at its best
  // offset; in phi order.
  struct Turned {
    float phi = 0.0f;
    Scored s;
  };
  V3 across(const V3& axis, float phi) const {
    V3 a = down().cross(axis);
    a = a.norm() > 1e-3f ? a.normalized() : V3::UnitX();
    return std::cos(phi) * a + std::sin(phi) * axis.cross(a).normalized();
  }
  std::vector<Turned> turned(const V3& axis, float step, int steps, float phi0, const Scored* around) const {
    std::vector<Turned> tried(std::size_t(2 * steps + 1));
    tbb::parallel_for(std::size_t(0), tried.size(), [&](std::size_t k) {
      const float phi = phi0 + float(int(k) - steps) * step;
      const V3 n = across(axis, phi);
      tried[k].phi = phi;
      if (std::abs(n.dot(down())) > std::sin(cfg.max_tilt) + 1e-6f) return;
      if (around == nullptr) {
        tried[k].s = coarse(n);
        return;
      }
      tried[k].s = turned_to(around->plane, n);
    });
    return tried;
  }
  // Finer normals and offsets around a coarse plane.
  // The normals are scored in parallel, then taken in their order (the first of equal scores).
  Scored refine(const Scored& c, float azimuth, float tilt, float tilt_step) const {
    const float da = 0.25f * cfg.angle_step, dt = 0.25f * tilt_step;
    const int tilt_steps = dt > 0.0f ? 3 : 0, columns = 2 * tilt_steps + 1;
    std::vector<Scored> tried(std::size_t(7 * columns));
    tbb::parallel_for(std::size_t(0), tried.size(), [&](std::size_t k) {
      const int i = int(k) / columns - 3, j = int(k) % columns - tilt_steps;
      const float tl = std::clamp(tilt + float(j) * dt, -cfg.max_tilt, cfg.max_tilt);
      const V3 n = normal_at(azimuth + float(i) * da, tl);
      tried[k] = turned_to(c.plane, n);
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
                  const SceneView& view, float tolerance);

}  // namespace uwgrasp::grasp::symmetry_detail
