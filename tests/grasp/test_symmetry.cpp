// Mirror symmetry from one view (grasp/symmetry.hpp), on analytic solids seen by a pinhole
// camera: a can standing upright, a box turned on the seafloor, a bottle-like cylinder lying with
// its axis tilted; the oracle is the solid itself.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "uwgrasp/grasp/symmetry.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::grasp;
using V3 = Eigen::Vector3f;

// L: x forward, y right, z down; the camera at L's origin looking forward and 35 degrees down;
// the seafloor 0.45 m below it.
constexpr float kFloor = 0.45f;

Pose camera_from_level() {
  // Optical frame: z forward, x right, y down; pitched down about L's y.
  Eigen::Matrix3d level_from_optical;
  level_from_optical.col(0) = Eigen::Vector3d::UnitY();
  level_from_optical.col(1) = Eigen::Vector3d::UnitZ();
  level_from_optical.col(2) = Eigen::Vector3d::UnitX();
  const double pitch = 35.0 * std::numbers::pi / 180.0;
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()) * level_from_optical;
  return T.inverse();
}

// A convex solid as a signed-distance-like test and surface samples with outward normals.
struct Solid {
  std::vector<V3> surface, normals;  // L
};

Solid can(const V3& base_centre, float radius, float height) {
  Solid s;
  for (int k = 0; k <= 60; ++k)
    for (int a = 0; a < 240; ++a) {
      const float t = 2.0f * std::numbers::pi_v<float> * float(a) / 240.0f;
      const V3 n(std::cos(t), std::sin(t), 0.0f);
      s.surface.push_back(base_centre + radius * n - V3(0, 0, height * float(k) / 60.0f));
      s.normals.push_back(n);
    }
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j) {
      const V3 q(radius * float(i) / 40.0f, radius * float(j) / 40.0f, 0.0f);
      if (q.norm() > radius) continue;
      s.surface.push_back(base_centre + q - V3(0, 0, height));
      s.normals.push_back(-V3::UnitZ());
    }
  return s;
}

// A box of `size` turned by R about its centre.
Solid box(const V3& centre, const V3& size, const Eigen::Matrix3f& R) {
  Solid s;
  const V3 h = 0.5f * size;
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i <= 50; ++i)
        for (int j = 0; j <= 50; ++j) {
          V3 q = V3::Zero();
          q[axis] = side * h[axis];
          q[u] = h[u] * (-1.0f + 2.0f * float(i) / 50.0f);
          q[v] = h[v] * (-1.0f + 2.0f * float(j) / 50.0f);
          V3 n = V3::Zero();
          n[axis] = side;
          s.surface.push_back(centre + R * q);
          s.normals.push_back(R * n);
        }
    }
  return s;
}

// An upright box turned by `yaw`, standing on base_centre.
Solid box(const V3& base_centre, const V3& size, float yaw) {
  return box(base_centre - V3(0, 0, 0.5f * size.z()), size, Eigen::AngleAxisf(yaw, V3::UnitZ()).toRotationMatrix());
}

// What the camera at L's origin sees of a convex solid: the surface facing it.
struct Sighted {
  std::vector<V3> level, normals, camera;
};
Sighted visible(const Solid& s) {
  Sighted v;
  const Pose T = camera_from_level();
  for (std::size_t i = 0; i < s.surface.size(); ++i) {
    if (s.normals[i].dot(-s.surface[i]) <= 1e-3f) continue;
    v.level.push_back(s.surface[i]);
    v.normals.push_back(s.normals[i]);
    v.camera.push_back((T * s.surface[i].cast<double>()).cast<float>());
  }
  return v;
}

// The seafloor z = kFloor in the camera frame, n.p + d = 0.
Eigen::Vector4f floor_in_camera() {
  const Pose T = camera_from_level();
  const Eigen::Vector3f n = (T.linear() * Eigen::Vector3d::UnitZ()).cast<float>();
  const Eigen::Vector3f p = (T * Eigen::Vector3d(0, 0, kFloor)).cast<float>();
  return {n.x(), n.y(), n.z(), -n.dot(p)};
}

// The scene's depth (the solid's seen side) with the seafloor: what symmetry is checked against.
struct Sight {
  SceneView v;
  const SceneView& view() const { return v; }
};
Sight sight_of(const Sighted& seen) {
  return {make_scene_view(seen.camera, floor_in_camera(), camera_from_level(), 0.003f, seen.level, 0.0015f)};
}

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

TEST(Symmetry, ATurnedBoxIsCompletedByItsTwoFacePlanes) {
  const V3 base(0.75f, -0.01f, kFloor), size(0.09f, 0.05f, 0.07f);
  const float yaw = 0.5f;
  const Sighted seen = visible(box(base, size, yaw));
  const Sight s = sight_of(seen);
  const std::vector<MirrorPlane> planes = find_symmetry(seen.level, s.view(), 0.0f, SymmetryConfig{});
  ASSERT_EQ(planes.size(), 2u) << "both of the box's upright symmetry planes";
  EXPECT_LT(std::abs(planes[0].normal.dot(planes[1].normal)), 1e-5f) << "square to each other";
  const Eigen::Matrix3f R = Eigen::AngleAxisf(yaw, V3::UnitZ()).toRotationMatrix();
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

}  // namespace
