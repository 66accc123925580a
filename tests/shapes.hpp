#pragma once
// Analytic test shapes with known normals and curvature, and shared test helpers.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::test {

// Path of a shared data file; skips the calling test when the shared folder is absent.
#define UWGRASP_DATA_OR_SKIP(var, rel)                                                      \
  const std::string var = std::string(UWGRASP_DATA_DIR) + "/" + rel;                       \
  if (!std::filesystem::exists(var)) GTEST_SKIP() << "shared data not found: " << var      \
                                                  << " (tests on real data need ../shared/data)"

// Grid of n x n points on the plane z = z0 (side `size`), jittered in-plane.
inline Cloud plane_grid(int n, float size, float z0, std::uint64_t seed = 1, float noise = 0) {
  Cloud c;
  Rng rng(seed);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const float x = -size / 2 + size * (i + 0.5f * float(rng.uniform())) / n;
      const float y = -size / 2 + size * (j + 0.5f * float(rng.uniform())) / n;
      c.points.emplace_back(x, y, z0 + noise * float(rng.normal()));
    }
  make_unorganised(c);
  return c;
}

// Points uniformly on a sphere (Fibonacci lattice).
inline Cloud sphere(int n, float r, const Eigen::Vector3f& centre) {
  Cloud c;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / n, rad = std::sqrt(1.0 - y * y);
    const double th = golden * i;
    c.points.push_back(centre + r * Eigen::Vector3d(std::cos(th) * rad, y, std::sin(th) * rad).cast<float>());
  }
  make_unorganised(c);
  return c;
}

// Surface samples of an axis-aligned box [lo, hi] with spacing `step`.
inline Cloud box_surface(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, float step) {
  Cloud c;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, d = (a + 2) % 3;
    for (float u = lo[b]; u <= hi[b] + 1e-6f; u += step)
      for (float v = lo[d]; v <= hi[d] + 1e-6f; v += step)
        for (float w : {lo[a], hi[a]}) {
          Eigen::Vector3f p;
          p[a] = w, p[b] = u, p[d] = v;
          c.points.push_back(p);
        }
  }
  make_unorganised(c);
  return c;
}

inline void append(Cloud& to, const Cloud& from) {
  to.points.insert(to.points.end(), from.points.begin(), from.points.end());
  to.colors.insert(to.colors.end(), from.colors.begin(), from.colors.end());
  make_unorganised(to);
}

inline void paint(Cloud& c, Rgb8 col) { c.colors.assign(c.size(), col); }

inline double angle_deg(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const double c = std::clamp(double(a.normalized().dot(b.normalized())), -1.0, 1.0);
  return std::acos(c) * 180.0 / std::numbers::pi;
}

}  // namespace uwgrasp::test
