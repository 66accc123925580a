// Mirror symmetry from one view (grasp/symmetry.hpp), on analytic solids seen by a pinhole
// camera: a can standing upright, a box turned on the seafloor, a bottle-like cylinder lying with
// its axis tilted; the oracle is the solid itself.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "symmetry_solids.hpp"
#include "uwgrasp/grasp/shape.hpp"
#include "uwgrasp/grasp/symmetry.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::grasp;
using namespace uwgrasp::grasp::test_solids;

TEST(Symmetry, ClassifiesAgainstWhatTheCameraSaw) {
  const Sighted seen = visible(can(V3(0.7f, 0.0f, kFloor), 0.03f, 0.1f));
  const Sight s = sight_of(seen);
  // A seen point is support; one 2 cm nearer the camera along its ray is in seen free space; one
  // 2 cm farther is hidden behind the can; a point under the seafloor is a violation.
  const V3 p = seen.level[seen.level.size() / 3];
  EXPECT_EQ(classify(s.view(), p, 0.003f), Seen::support);
  EXPECT_EQ(classify(s.view(), p * (1.0f - 0.02f / p.norm()), 0.003f), Seen::violation);
  EXPECT_EQ(classify(s.view(), p * (1.0f + 0.02f / p.norm()), 0.003f), Seen::hidden);
  EXPECT_EQ(classify(s.view(), V3(0.7f, 0.2f, kFloor + 0.02f), 0.003f), Seen::violation);
  // Beside the can, above the visible seafloor: free space the camera saw through.
  EXPECT_EQ(classify(s.view(), V3(0.7f, 0.15f, kFloor - 0.05f), 0.003f), Seen::violation);
}

// The view's bins and the surface cells without a floor call are the floor's: random values,
// every bin boundary near zero, values past the clamp; points in and around the cells, and NaN.
TEST(Symmetry, BinsAndCellsAreTheFloorsOfTheirCoordinates) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<float> wide(-3.0f, 3.0f);
  const float inverse = 1.0f / 0.003f;
  const auto reference = [](float v, float inv) { return int(std::floor(std::clamp(v * inv, -1e8f, 1e8f))); };
  for (int i = 0; i < 200000; ++i) {
    const float v = wide(gen);
    ASSERT_EQ(sight_detail::bin_of(v, inverse), reference(v, inverse)) << v;
  }
  for (int b = -2000; b <= 2000; ++b)
    for (const float v : {float(b) * 0.003f, std::nextafter(float(b) * 0.003f, -1.0f), std::nextafter(float(b) * 0.003f, 1.0f)})
      ASSERT_EQ(sight_detail::bin_of(v, inverse), reference(v, inverse)) << v;
  for (const float v : {1e12f, -1e12f, 0.0f, -0.0f, 1e-30f, -1e-30f, 16777217.0f * 0.003f, -16777217.0f * 0.003f})
    EXPECT_EQ(sight_detail::bin_of(v, inverse), reference(v, inverse)) << v;

  const Sighted seen = visible(can(V3(0.7f, 0.0f, kFloor), 0.03f, 0.1f));
  const Sight sight = sight_of(seen);
  const SurfaceCells& cells = sight.view().surface;
  ASSERT_FALSE(cells.marked.empty());
  const auto contains = [&](const V3& p) {
    const V3 q = (p - cells.origin) / cells.cell;
    const int i = int(std::floor(q.x())), j = int(std::floor(q.y())), k = int(std::floor(q.z()));
    if (i < 0 || j < 0 || k < 0 || i >= cells.nx || j >= cells.ny || k >= cells.nz) return false;
    return cells.marked[(std::size_t(k) * std::size_t(cells.ny) + std::size_t(j)) * std::size_t(cells.nx) + std::size_t(i)] != 0;
  };
  const V3 size = cells.cell * V3(float(cells.nx), float(cells.ny), float(cells.nz));
  std::uniform_real_distribution<float> unit(-0.1f, 1.1f);
  std::size_t inside = 0;
  for (int i = 0; i < 200000; ++i) {
    const V3 p = cells.origin + V3(unit(gen), unit(gen), unit(gen)).cwiseProduct(size);
    ASSERT_EQ(cells.contains(p), contains(p)) << p.transpose();
    inside += contains(p);
  }
  EXPECT_GT(inside, 100u);
  EXPECT_FALSE(cells.contains(V3::Constant(std::nanf(""))));
}

TEST(Symmetry, AnUprightCanIsMirroredAboutAPlaneThroughItsAxis) {
  const V3 base(0.7f, 0.02f, kFloor);
  const float radius = 0.03f;
  const Sighted seen = visible(can(base, radius, 0.1f));
  const Sight s = sight_of(seen);
  const std::vector<MirrorPlane> planes = find_symmetry(seen.level, s.view(), 0.0f, SymmetryConfig{});
  ASSERT_FALSE(planes.empty());
  for (const MirrorPlane& p : planes) {
    EXPECT_LT(std::abs(p.normal.z()), 0.05f) << "a can's symmetry planes are upright";
    EXPECT_LT(std::abs(p.normal.dot(base) - p.offset), 0.003f) << "the plane runs through the axis";
    EXPECT_LE(p.violations, SymmetryConfig{}.max_violations);
  }
  std::vector<V3> back, back_normals;
  mirror_points(seen.level, seen.normals, planes, s.view(), 0.003f, back, back_normals);
  ASSERT_GT(back.size(), seen.level.size() / 4) << "the can's far side is completed";
  std::size_t far_side = 0;
  for (std::size_t i = 0; i < back.size(); ++i) {
    const V3 radial(back[i].x() - base.x(), back[i].y() - base.y(), 0.0f);
    const bool wall = std::abs(back_normals[i].z()) < 0.5f;
    if (wall) {
      EXPECT_NEAR(radial.norm(), radius, 0.003f) << "mirrored points lie on the can";
      EXPECT_GT(back_normals[i].dot(radial.normalized()), 0.95f) << "with outward normals";
    }
    far_side += radial.x() > 0.5f * radius;  // the half facing away from the camera
    EXPECT_EQ(classify(s.view(), back[i], 0.003f), Seen::hidden);
  }
  EXPECT_GT(far_side, back.size() / 4);
}

// The second plane searched freely near square to the first (perpendicular: false) finds the
// other face plane too: on a noiseless box, the free search has nothing to pull it off square.
TEST(Symmetry, ATurnedBoxIsCompletedByItsTwoFacePlanes) {
  const V3 base(0.75f, -0.01f, kFloor), size(0.09f, 0.05f, 0.07f);
  const float yaw = 0.5f;
  const Sighted seen = visible(box(base, size, yaw));
  const Sight s = sight_of(seen);
  const Eigen::Matrix3f R = Eigen::AngleAxisf(yaw, V3::UnitZ()).toRotationMatrix();
  SymmetryConfig free;
  free.perpendicular = false;
  const std::vector<MirrorPlane> freely = find_symmetry(seen.level, s.view(), 0.0f, free);
  EXPECT_EQ(freely.size(), 2u) << "searched freely";
  for (const MirrorPlane& p : freely)
    EXPECT_GT(std::max(std::abs(p.normal.dot(R.col(0))), std::abs(p.normal.dot(R.col(1)))), 0.99f)
        << "searched freely: " << p.normal.transpose();
  const std::vector<MirrorPlane> planes = find_symmetry(seen.level, s.view(), 0.0f, SymmetryConfig{});
  ASSERT_EQ(planes.size(), 2u) << "both of the box's upright symmetry planes";
  EXPECT_LT(std::abs(planes[0].normal.dot(planes[1].normal)), 1e-5f) << "square to each other";
  for (const MirrorPlane& p : planes) {
    const float along_x = std::abs(p.normal.dot(R.col(0))), along_y = std::abs(p.normal.dot(R.col(1)));
    EXPECT_GT(std::max(along_x, along_y), 0.99f) << "normal along a face normal: " << p.normal.transpose();
    EXPECT_LT(std::abs(p.normal.dot(base) - p.offset), 0.003f) << "through the box's centre";
  }
  std::vector<V3> back, back_normals;
  mirror_points(seen.level, seen.normals, planes, s.view(), 0.003f, back, back_normals);
  ASSERT_FALSE(back.empty());
  bool faces[2][2] = {{false, false}, {false, false}};  // faces reached: -x/+x, -y/+y
  for (const V3& q : back) {
    const V3 local = R.transpose() * (q - (base - V3(0, 0, 0.5f * size.z())));
    for (int a = 0; a < 3; ++a) EXPECT_LE(std::abs(local[a]), 0.5f * size[a] + 0.002f) << "inside the box";
    for (int a = 0; a < 2; ++a)
      if (std::abs(std::abs(local[a]) - 0.5f * size[a]) < 0.002f) faces[a][local[a] > 0] = true;
  }
  // Both upright faces the camera cannot see (their outward normals point away from it) are
  // completed: here the box's +x and -y faces.
  const V3 centre = base - V3(0, 0, 0.5f * size.z());
  for (int a = 0; a < 2; ++a) {
    const int hidden_side = R.col(a).dot(-centre) < 0.0f ? 1 : 0;
    EXPECT_TRUE(faces[a][hidden_side]) << "face " << a << (hidden_side ? " +" : " -");
  }
}

// A square-section box tilted two ways (docs/results/holds/probe/tilted.yaml), its seen side
// with 1.5 mm of depth noise. Its diagonal plane maps the two seen side faces onto each other
// and outscores either face plane, but adds nothing behind them, and the plane square to it
// tilts out of reach: kept alone it left the back unmirrored and grasps closed on the minimum
// thickness. The two face planes together complete it.
TEST(Symmetry, ATiltedSquareBoxIsCompletedByItsFacePlanesNotADiagonal) {
  const Eigen::Matrix3f world = (Eigen::AngleAxisf(0.9f, V3::UnitZ()) * Eigen::AngleAxisf(0.3f, V3::UnitY()) *
                                 Eigen::AngleAxisf(0.5f, V3::UnitX())).toRotationMatrix();
  const Eigen::Matrix3f flip = V3(1.0f, -1.0f, -1.0f).asDiagonal();  // world (z up) to L (z down)
  const Eigen::Matrix3f R = flip * world * flip;
  const Sighted all = visible(box(V3(0.82f, 0.0f, kFloor - 0.035f), V3(0.06f, 0.06f, 0.09f), R));
  std::mt19937 rng(1);
  std::normal_distribution<float> depth(0.0f, 0.0015f);
  const Pose T = camera_from_level();
  Sighted seen;  // above the seafloor, each point moved along its ray
  for (std::size_t i = 0; i < all.level.size(); ++i) {
    if (all.level[i].z() >= kFloor) continue;
    const V3 c = all.camera[i] * (1.0f + depth(rng) / all.camera[i].norm());
    seen.camera.push_back(c);
    seen.level.push_back((T.inverse() * c.cast<double>()).cast<float>());
    seen.normals.push_back(all.normals[i]);
  }
  const Sight s = sight_of(seen);
  const std::vector<MirrorPlane> planes = find_symmetry(seen.level, s.view(), 0.0015f, SymmetryConfig{});
  ASSERT_EQ(planes.size(), 2u);
  const V3 n = planes[0].normal;
  EXPECT_GT(std::max(std::abs(n.dot(R.col(0))), std::abs(n.dot(R.col(1)))), 0.99f)
      << "the first plane's normal along a side face's, not the diagonal: " << n.transpose();
  // (The second comes out upright here, 27 degrees off the other face plane: the upright prior
  // and one noisy view do not fix its turn - docs/results/grasps-that-hold.md.)
  EXPECT_LT(std::abs(n.dot(planes[1].normal)), 1e-5f) << "square to the first";
}

TEST(Symmetry, KeptPlanesNeverPutTheSeenSideIntoSeenFreeSpace) {
  // Random blobs of points: whatever plane is kept respects the violation limit, and the search
  // gives the same planes however often it runs.
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  for (int trial = 0; trial < 5; ++trial) {
    Sighted seen;
    const Pose T = camera_from_level();
    for (int i = 0; i < 800; ++i) {
      const V3 p(0.7f + noise(rng), noise(rng), kFloor - 0.05f + noise(rng));
      seen.level.push_back(p);
      seen.normals.push_back(-p.normalized());
      seen.camera.push_back((T * p.cast<double>()).cast<float>());
    }
    const Sight s = sight_of(seen);
    const SymmetryConfig cfg;
    const auto planes = find_symmetry(seen.level, s.view(), 0.0f, cfg);
    const auto again = find_symmetry(seen.level, s.view(), 0.0f, cfg);
    ASSERT_EQ(planes.size(), again.size());
    for (std::size_t k = 0; k < planes.size(); ++k) {
      EXPECT_EQ(planes[k].normal, again[k].normal);
      EXPECT_EQ(planes[k].offset, again[k].offset);
      EXPECT_LE(planes[k].violations, cfg.max_violations);
      EXPECT_GE(planes[k].support, cfg.min_support);
    }
  }
}

TEST(Symmetry, OffOrTooFewPointsFindsNothing) {
  const Sighted seen = visible(can(V3(0.7f, 0.0f, kFloor), 0.03f, 0.1f));
  const Sight s = sight_of(seen);
  SymmetryConfig off;
  off.enabled = false;
  EXPECT_TRUE(find_symmetry(seen.level, s.view(), 0.0f, off).empty());
  EXPECT_TRUE(find_symmetry(std::span(seen.level).first(5), s.view(), 0.0f, SymmetryConfig{}).empty());
}

// The completed shape's symmetry planes of a bottle lying on the seafloor, with L in
// `level_from_true` (identity: the seafloor level in L; a turn: the same frame seen with L tilted
// against it, as on a sloping seafloor with the vehicle's attitude against gravity given).
std::vector<MirrorPlane> lying_bottle_planes(const Eigen::Matrix3f& level_from_true) {
  const Eigen::Matrix3f& Q = level_from_true;
  const float radius = 0.03f;
  const V3 axis(std::cos(0.6f), std::sin(0.6f), 0.0f), centre(0.75f, 0.0f, kFloor - radius);
  const Sighted seen = visible(cylinder(centre, axis, radius, 0.16f));
  std::vector<V3> level, normals;
  for (std::size_t i = 0; i < seen.level.size(); ++i)
    level.push_back(Q * seen.level[i]), normals.push_back(Q * seen.normals[i]);
  const V3 up = Q * -V3::UnitZ();  // the seafloor z = kFloor, turned about L's origin (the camera)
  const FloorPlane floor(up.x(), up.y(), up.z(), kFloor);
  const SceneSight scene{seen.camera, floor_in_camera()};  // the camera sees the same either way
  Frames frames;
  Pose turn = Pose::Identity();
  turn.linear() = Q.cast<double>();
  frames.level_from_camera = turn * camera_from_level().inverse();
  return complete_shape(level, seen.camera, frames, floor, ShapeConfig{}, normals, &scene).planes;
}

// Objects rest on the seafloor, so their symmetry is searched upright to it: the same frame with
// L tilted 20 degrees either way against the seafloor (a sloping seafloor, the IMU's attitude
// given) gives the same planes, turned with L. Searched upright to L, the tilted frames kept
// another plane through the bottle's axis (a cylinder's planes through its axis all fit; which
// one is kept follows the upright), and judged top-1s on the lying bottle on a 20 degree slope
// held 60 of 140 (docs/results/grasps-that-hold.md).
TEST(Symmetry, OnASlopingSeafloorThePlanesTurnWithTheSeafloor) {
  const std::vector<MirrorPlane> level = lying_bottle_planes(Eigen::Matrix3f::Identity());
  ASSERT_FALSE(level.empty());
  for (const float degrees : {-20.0f, 20.0f}) {
    const Eigen::Matrix3f Q =
        Eigen::AngleAxisf(degrees * std::numbers::pi_v<float> / 180.0f, V3::UnitY())
            .toRotationMatrix();
    const std::vector<MirrorPlane> sloped = lying_bottle_planes(Q);
    ASSERT_EQ(sloped.size(), level.size()) << degrees << " degrees";
    // The same planes within 2 degrees and 2 mm (their order may swap on a near tie).
    for (const MirrorPlane& p : level) {
      const auto same = [&](const MirrorPlane& q) {  // (n, d) and (-n, -d) are one plane
        const float side = q.normal.dot(Q * p.normal) < 0.0f ? -1.0f : 1.0f;
        return side * q.normal.dot(Q * p.normal) > 0.9995f &&
               std::abs(side * q.offset - p.offset) < 2e-3f;
      };
      EXPECT_TRUE(std::any_of(sloped.begin(), sloped.end(), same))
          << degrees << " degrees: no plane turned from " << p.normal.transpose() << ", "
          << p.offset;
    }
  }
}

}  // namespace
