// The shells of an object's shape (ObjectShape::points / normals and core_points / core_normals,
// built in parallel runs of slabs into one list each): the cells, normals and order that the
// definition in shape.hpp gives, recomputed cell by cell from the finished grid.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <vector>

#include "objects.hpp"
#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/grasp/reach.hpp"
#include "uwgrasp/grasp/shape.hpp"

namespace uwgrasp::grasp {
namespace {
using V3 = Eigen::Vector3f;

struct Shell {
  std::vector<V3> points, normals;
};

// One sweep, k then j then i, over every cell, with no shortcut: a cell of `part` (never free,
// seen or mirrored) with a face neighbour `outside` (off the grid is free), optionally not
// touching a mirrored cell, whose 5 x 5 x 5 block's cells not `outside` have a nonzero offset
// sum; its centre, and the negated sum normalised.
template <class Part, class Outside>
Shell brute_shell(const ObjectShape& s, Part part, Outside outside, bool mirrored_surface) {
  const auto get = [&](int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= s.nx || j >= s.ny || k >= s.nz) return Occupancy::free;
    return s.cells[(std::size_t(k) * std::size_t(s.ny) + std::size_t(j)) * std::size_t(s.nx) +
                   std::size_t(i)];
  };
  Shell out;
  for (int k = 0; k < s.nz; ++k)
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) {
        const Occupancy o = get(i, j, k);
        if (o == Occupancy::free || o == Occupancy::seen || o == Occupancy::mirrored || !part(o))
          continue;
        const bool boundary = outside(get(i - 1, j, k)) || outside(get(i + 1, j, k)) ||
                              outside(get(i, j - 1, k)) || outside(get(i, j + 1, k)) ||
                              outside(get(i, j, k - 1)) || outside(get(i, j, k + 1));
        if (!boundary) continue;
        bool by_mirrored = false;
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di)
              by_mirrored |= get(i + di, j + dj, k + dk) == Occupancy::mirrored;
        if (mirrored_surface && by_mirrored) continue;
        Eigen::Vector3i sum = Eigen::Vector3i::Zero();
        for (int dk = -2; dk <= 2; ++dk)
          for (int dj = -2; dj <= 2; ++dj)
            for (int di = -2; di <= 2; ++di)
              if (!outside(get(i + di, j + dj, k + dk))) sum -= Eigen::Vector3i(di, dj, dk);
        const V3 away = sum.cast<float>();
        if (away.norm() < 1e-3f) continue;
        out.points.push_back(s.origin + s.voxel * V3(float(i), float(j), float(k)));
        out.normals.push_back(away.normalized());
      }
  return out;
}

void expect_same(const Shell& want, const std::vector<V3>& points, const std::vector<V3>& normals) {
  ASSERT_EQ(points.size(), want.points.size());
  ASSERT_EQ(normals.size(), want.normals.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_EQ(points[i], want.points[i]) << i;
    ASSERT_EQ(normals[i], want.normals[i]) << i;
  }
}

// The barbell and the ring on the seafloor, seen from two sides, with the mirror search on (so
// that some cells are mirrored), at 1 and 2 threads.
TEST(ShapeShell, ShellsAreTheDefinitionCellByCell) {
  std::size_t mirrored = 0;
  for (const auto object : {fixtures::Object::barbell, fixtures::Object::ring})
    for (const double yaw : {0.0, 0.9})
      for (const int threads : {1, 2}) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                        std::size_t(threads));
        fixtures::View view;
        view.yaw = yaw;
        const fixtures::ObjectCloud obj = fixtures::render_object(object, view, 20000);
        FrameConfig fc;
        fc.camera.rpy.y() = obj.camera_pitch;
        const Frames frames = make_frames(fc);
        const Eigen::Vector3d n = obj.camera_from_world.linear().col(2);
        const FloorPlane floor_c(float(n.x()), float(n.y()), float(n.z()),
                                 float(-n.dot(obj.camera_from_world.translation())));
        const Surroundings scene{obj.cloud.points, true, floor_c};
        const SceneSight sight{obj.cloud.points, floor_c};
        const std::vector<V3> level = points_to_level(obj.cloud.points, frames);
        const std::vector<V3> normals = directions_to_level(obj.cloud.normals, frames);
        const ObjectShape s =
            complete_shape(level, obj.cloud.points, frames, level_plane(scene, frames),
                           ShapeConfig{}, normals, &sight);
        SCOPED_TRACE(testing::Message()
                     << "object " << int(object) << " yaw " << yaw << " threads " << threads);
        ASSERT_GT(s.count(Occupancy::assumed) + s.count(Occupancy::thin), 0u);
        mirrored += s.count(Occupancy::mirrored);
        const auto any = [](Occupancy) { return true; };
        const auto is_free = [](Occupancy o) { return o == Occupancy::free; };
        const auto is_thin = [](Occupancy o) { return o == Occupancy::thin; };
        const auto beyond_core = [](Occupancy o) {
          return o == Occupancy::free || o == Occupancy::assumed || o == Occupancy::mirrored;
        };
        const Shell outer = brute_shell(s, any, is_free, true),
                    core = brute_shell(s, is_thin, beyond_core, false);
        EXPECT_GT(outer.points.size(), 100u);
        EXPECT_GT(core.points.size(), 100u);
        expect_same(outer, s.points, s.normals);
        expect_same(core, s.core_points, s.core_normals);
      }
  EXPECT_GT(mirrored, 0u);  // the shell's skip by mirrored cells was tried
}

}  // namespace
}  // namespace uwgrasp::grasp
