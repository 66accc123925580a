#pragma once
// The voxel grid of an object's shape as complete_shape builds it, and the shell of its unseen
// part: the surface points and normals a gripper must not pass through. Internal to grasp/
// (shape.cpp); templates, so that the tests of which cells belong to a part inline.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "uwgrasp/grasp/shape.hpp"

namespace uwgrasp::grasp::shape_detail {

using V3 = Eigen::Vector3f;

struct Grid {
  ObjectShape& s;
  std::size_t index(int i, int j, int k) const {
    return (std::size_t(k) * std::size_t(s.ny) + std::size_t(j)) * std::size_t(s.nx) +
           std::size_t(i);
  }
  bool inside(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < s.nx && j < s.ny && k < s.nz;
  }
  Eigen::Vector3i cell(const V3& p) const { return s.cell_of(p); }
  V3 centre(int i, int j, int k) const {
    return s.origin + s.voxel * V3(float(i), float(j), float(k));
  }
  Occupancy get(int i, int j, int k) const {
    return inside(i, j, k) ? s.cells[index(i, j, k)] : Occupancy::free;
  }
};

// Whether a face neighbour of (i, j, k) is `outside`; a voxel off the grid's faces reads its
// neighbours by strides, without a bounds test each (the shells scan every voxel of the grid).
template <class Outside>
bool on_boundary(Grid g, int i, int j, int k, Outside outside) {
  const ObjectShape& s = g.s;
  if (i >= 1 && j >= 1 && k >= 1 && i + 1 < s.nx && j + 1 < s.ny && k + 1 < s.nz) {
    const std::ptrdiff_t sy = s.nx, sz = std::ptrdiff_t(s.nx) * s.ny;
    const Occupancy* c = s.cells.data() + g.index(i, j, k);
    return outside(c[-1]) || outside(c[1]) || outside(c[-sy]) || outside(c[sy]) ||
           outside(c[-sz]) || outside(c[sz]);
  }
  return outside(g.get(i - 1, j, k)) || outside(g.get(i + 1, j, k)) ||
         outside(g.get(i, j - 1, k)) || outside(g.get(i, j + 1, k)) ||
         outside(g.get(i, j, k - 1)) || outside(g.get(i, j, k + 1));
}

// Whether a mirrored voxel touches (i, j, k): the mirrored points already give the surface there,
// with the seen side's normals, which a voxel shell only approximates.
inline bool by_mirrored(Grid g, int i, int j, int k) {
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di)
        if (g.get(i + di, j + dj, k + dk) == Occupancy::mirrored) return true;
  return false;
}

// Minus the sum of the offsets of the voxels in the 5 x 5 x 5 block around (i, j, k) that are
// not `outside`: a block wholly in the grid is read by strides, without a bounds test per voxel.
template <class Outside>
V3 away_from_mass(Grid g, int i, int j, int k, Outside outside) {
  const ObjectShape& s = g.s;
  Eigen::Vector3i sum = Eigen::Vector3i::Zero();
  if (i >= 2 && j >= 2 && k >= 2 && i + 2 < s.nx && j + 2 < s.ny && k + 2 < s.nz) {
    const std::ptrdiff_t sy = s.nx, sz = std::ptrdiff_t(s.nx) * s.ny;
    const Occupancy* c = s.cells.data() + g.index(i, j, k);
    // Without a branch per voxel: a row's count and its first moment (the 5 x 5 x 5 block of a
    // shell voxel is half in, half out, and a branch on each mispredicted half the time).
    for (int dk = -2; dk <= 2; ++dk)
      for (int dj = -2; dj <= 2; ++dj) {
        const Occupancy* row = c + dk * sz + dj * sy;
        int count = 0, moment = 0;
        for (int di = -2; di <= 2; ++di) {
          const int in = !outside(row[di]);
          count += in, moment += in * di;
        }
        sum -= Eigen::Vector3i(moment, count * dj, count * dk);
      }
  } else {
    for (int dk = -2; dk <= 2; ++dk)
      for (int dj = -2; dj <= 2; ++dj)
        for (int di = -2; di <= 2; ++di)
          if (!outside(g.get(i + di, j + dj, k + dk))) sum -= Eigen::Vector3i(di, dj, dk);
  }
  return sum.cast<float>();
}

// Whether the 8 cells from c on are all free: most of a grid is (87 % of mOSD_learn17's object's),
// and the shells skip those 8 at a time.
inline bool free_run(const Occupancy* c) {
  static_assert(sizeof(Occupancy) == 1 && Occupancy::free == Occupancy{0});
  std::uint64_t word;
  std::memcpy(&word, c, sizeof word);
  return word == 0;
}

// Calls f(i, j, k) for each cell of slabs [k0, k1) that `part` takes, that is neither free, seen
// nor mirrored, and that has a face neighbour `outside`: the shell's candidates, in sweep order.
template <class Part, class Outside, class F>
void for_candidates(Grid g, int k0, int k1, Part part, Outside outside, F f) {
  const ObjectShape& s = g.s;
  for (int k = k0; k < k1; ++k)
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) {
        if (i + 8 <= s.nx && free_run(s.cells.data() + g.index(i, j, k))) {
          i += 7;
          continue;
        }
        const Occupancy o = s.cells[g.index(i, j, k)];
        if (o != Occupancy::free && o != Occupancy::seen && o != Occupancy::mirrored && part(o) &&
            on_boundary(g, i, j, k, outside))
          f(i, j, k);
      }
}

// The unseen voxels (`part` says which) next to one outside the part (`outside`), with normals
// pointing away from the part's mass around them (the sum of the offsets of the part's voxels
// in a 5 x 5 x 5 block, negated); with `mirrored_surface`, not where mirrored points lie.
template <class Part, class Outside>
void shell(Grid g, Part part, Outside outside, bool mirrored_surface, std::vector<V3>& points,
           std::vector<V3>& normals) {
  // Runs of kSlabs slabs of constant k in parallel. A run's points are among its candidates:
  // counted first, they give each run its own stretch of the lists, which the runs fill in
  // parallel and which then close ranks in run order - the same points in the same order as one
  // sweep, with one allocation a list (a list a run, grown by doubling, made ~1,000 a frame). On
  // the six bench frames the candidates were at most 1.4 times the points kept.
  constexpr int kSlabs = 4;
  const int nz = g.s.nz, runs = (nz + kSlabs - 1) / kSlabs;
  std::vector<std::size_t> start(std::size_t(runs) + 1, points.size()),
      filled(std::size_t(runs), 0);
  tbb::parallel_for(0, runs, [&](int r) {
    std::size_t n = 0;
    for_candidates(g, r * kSlabs, std::min(nz, (r + 1) * kSlabs), part, outside,
                   [&](int, int, int) { ++n; });
    start[std::size_t(r) + 1] = n;
  });
  for (std::size_t r = 0; r < std::size_t(runs); ++r) start[r + 1] += start[r];
  points.resize(start.back()), normals.resize(start.back());
  tbb::parallel_for(0, runs, [&](int r) {
    std::size_t& n = filled[std::size_t(r)];
    for_candidates(
        g, r * kSlabs, std::min(nz, (r + 1) * kSlabs), part, outside, [&](int i, int j, int k) {
          if (mirrored_surface && by_mirrored(g, i, j, k)) return;
          const V3 away = away_from_mass(g, i, j, k, outside);
          if (away.norm() < 1e-3f) return;  // no side faces away from the mass: not a surface
          points[start[std::size_t(r)] + n] = g.centre(i, j, k),
                                         normals[start[std::size_t(r)] + n] = away.normalized();
          ++n;
        });
  });
  std::size_t end = start[0];
  for (std::size_t r = 0; r < std::size_t(runs); ++r) {
    const auto from = std::ptrdiff_t(start[r]), count = std::ptrdiff_t(filled[r]),
               to = std::ptrdiff_t(end);
    if (from != to) {  // earlier, never into its own stretch: a forward move is safe
      std::move(points.begin() + from, points.begin() + from + count, points.begin() + to);
      std::move(normals.begin() + from, normals.begin() + from + count, normals.begin() + to);
    }
    end += filled[r];
  }
  points.resize(end), normals.resize(end);
}

}  // namespace uwgrasp::grasp::shape_detail
