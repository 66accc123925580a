// The walk along a line through a shape grid (grasp/shape.hpp: extent_along), which looks up only
// some of its points; the oracle is the walk that looks up every one.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "uwgrasp/grasp/shape.hpp"

namespace {
using namespace uwgrasp::grasp;
using V3 = Eigen::Vector3f;

// Every point looked up, as the samplers did before extent_along skipped any.
float every_point(const ObjectShape& shape, const V3& p, const V3& u, float limit, float gap) {
  const float step = 0.5f * shape.voxel;
  float last = 0.0f;
  for (float t = step; t <= limit + gap; t += step) {
    if (shape.occupied(p + t * u))
      last = t;
    else if (t - last > gap)
      break;
  }
  return last;
}

// A grid of solid balls, some hollow, with single free cells scattered through the solid (the
// gaps shorter than `gap` that a walk must cross) and occupied specks in the free space.
ObjectShape balls(std::mt19937& rng, float voxel) {
  ObjectShape s;
  s.voxel = voxel;
  s.origin = V3(0.1f, -0.2f, 0.3f);
  std::uniform_int_distribution<int> side(1, 40);
  s.nx = side(rng), s.ny = side(rng), s.nz = side(rng);
  s.cells.assign(std::size_t(s.nx * s.ny * s.nz), Occupancy::free);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int b = 0; b < 4; ++b) {
    const V3 c(unit(rng) * float(s.nx), unit(rng) * float(s.ny), unit(rng) * float(s.nz));
    const float r = 2.0f + 10.0f * unit(rng), hollow = unit(rng) < 0.3f ? 0.6f * r : -1.0f;
    for (int k = 0; k < s.nz; ++k)
      for (int j = 0; j < s.ny; ++j)
        for (int i = 0; i < s.nx; ++i) {
          const float d = (V3(float(i), float(j), float(k)) - c).norm();
          if (d <= r && d >= hollow)
            s.cells[std::size_t((k * s.ny + j) * s.nx + i)] = Occupancy::assumed;
        }
  }
  for (Occupancy& o : s.cells) {
    const float x = unit(rng);
    if (o != Occupancy::free && x < 0.03f)
      o = Occupancy::free;
    else if (o == Occupancy::free && x < 0.01f)
      o = Occupancy::seen;
  }
  return s;
}

TEST(ShapeWalk, ExtentAlongIsTheWalkThatLooksUpEveryPoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  int walks = 0, reaching = 0, stopped_early = 0;
  for (int grid = 0; grid < 60; ++grid) {
    const float voxel = grid % 3 == 0 ? 0.0025f : grid % 3 == 1 ? 0.001f : 0.0173f;
    const ObjectShape s = balls(rng, voxel);
    const V3 size = voxel * V3(float(s.nx), float(s.ny), float(s.nz));
    for (int w = 0; w < 400; ++w) {
      // From inside the grid or a little outside it, in any direction.
      const V3 p =
          s.origin + V3(unit(rng) * 1.2f - 0.1f, unit(rng) * 1.2f - 0.1f, unit(rng) * 1.2f - 0.1f)
                         .cwiseProduct(size);
      const V3 u = V3(normal(rng), normal(rng), normal(rng)).normalized();
      const float limit = unit(rng) * size.maxCoeff();
      // Gaps of whole and fractional steps, below a step, and far past the most skipped.
      const float steps[] = {4.0f, 4.5f, 3.999f, 1.0f, 0.3f, 2.01f, 40.0f};
      const float gap = steps[w % 7] * 0.5f * voxel;
      const float expected = every_point(s, p, u, limit, gap);
      ASSERT_EQ(extent_along(s, p, u, limit, gap), expected)
          << "grid " << grid << " walk " << w << " gap " << gap << " limit " << limit;
      ++walks, reaching += expected > limit, stopped_early += expected > 0.0f && expected <= limit;
    }
  }
  // The walks cover the cases: through solid past the limit, and stopped by a gap before it.
  EXPECT_GT(reaching, walks / 50);
  EXPECT_GT(stopped_early, walks / 10);
}

// The palm back-off's line scan, four points a go, against the scan that looks up one point at a
// time from the far end: the same step on every line, through balls, specks and the grid's edges,
// with ranges that start or end outside the grid and ranges shorter than four.
TEST(ShapeWalk, LastOccupiedIsTheScanOfOnePointAtATime) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), sym(-1.0f, 1.0f);
  std::uniform_int_distribution<int> bound(-20, 140);
  std::size_t lines = 0, hits = 0;
  for (int g = 0; g < 40; ++g) {
    const ObjectShape s = balls(rng, 0.002f + 0.004f * unit(rng));
    const V3 size = s.voxel * V3(float(s.nx), float(s.ny), float(s.nz));
    for (int l = 0; l < 200; ++l, ++lines) {
      const V3 base = s.origin + size.cwiseProduct(V3(unit(rng), unit(rng), unit(rng)) * 1.4f -
                                                   V3::Constant(0.2f));
      const V3 u = V3(sym(rng), sym(rng), sym(rng)).normalized();
      const float step = 0.5f * s.voxel;
      int first = bound(rng), last = bound(rng);
      if (first > last) std::swap(first, last);
      int expected = first - 1;
      for (int i = last; i >= first; --i)
        if (s.occupied(base - float(i) * step * u)) {
          expected = i;
          break;
        }
      ASSERT_EQ(last_occupied(s, base, u, step, first, last), expected)
          << "grid " << g << " line " << l;
      hits += expected >= first;
    }
  }
  EXPECT_GT(hits, lines / 10);  // both answers, many times (1,067 hits of 8,000)
  EXPECT_LT(hits, lines - lines / 10);
  const ObjectShape none;
  EXPECT_EQ(last_occupied(none, V3::Zero(), V3::UnitX(), 0.001f, 3, 9), 2);
  EXPECT_EQ(last_occupied(balls(rng, 0.003f), V3::Zero(), V3::UnitX(), 0.001f, 5, 4),
            4);  // empty range
}

TEST(ShapeWalk, ExtentAlongOnDegenerateInput) {
  ObjectShape empty;
  empty.voxel = 0.002f;
  EXPECT_EQ(extent_along(empty, V3::Zero(), V3::UnitX(), 0.1f, 0.004f), 0.0f);
  std::mt19937 rng(3);
  const ObjectShape s = balls(rng, 0.002f);
  const V3 nan = V3::Constant(std::numeric_limits<float>::quiet_NaN());
  EXPECT_EQ(extent_along(s, nan, V3::UnitX(), 0.1f, 0.004f), 0.0f);
  EXPECT_EQ(extent_along(s, s.origin, nan, 0.1f, 0.004f), 0.0f);
  EXPECT_EQ(extent_along(s, s.origin, V3::UnitY(), -1.0f, 0.004f), 0.0f);  // nothing to walk
}

}  // namespace
