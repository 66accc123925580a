// The world's geometric queries against analytic shapes: rays, triangle-box overlap, inside
// tests (analytic primitives against the same shapes read as mesh files) and nearest points.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/sim/query.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::sim;
using V3 = Eigen::Vector3d;

Pose at(const V3& t) {
  Pose p = Pose::Identity();
  p.translation() = t;
  return p;
}

Scene one_object(std::vector<Part> parts, const Pose& pose = Pose::Identity(), bool floor = false) {
  Scene s;
  s.name = "query scene";
  s.seafloor.enabled = floor;
  s.objects.push_back({"thing", std::move(parts), pose, {200, 30, 30}, true});
  return s;
}

// Writes a mesh as a Wavefront OBJ file (read back through assimp as a mesh part).
std::string write_obj(const Mesh& m, const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() / std::string("uwgrasp_query_").append(name).append(".obj");
  std::ofstream f(path);
  for (const auto& v : m.vertices) f << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : m.triangles) f << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  return path.string();
}

TEST(Query, RayMeetsTheBoxFaceWithItsOutwardNormalAndNamesTheObject) {
  const World w(one_object({{Shape{.size = V3(0.1, 0.2, 0.3)}, Pose::Identity()}}, at(V3(1, 0, 0.5)), true));
  const RayHit h = first_hit(w, {V3(0, 0, 0.5), V3::UnitX(), 10});
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 0.95, 1e-6);
  EXPECT_NEAR(h.normal.x(), -1.0, 1e-9);
  EXPECT_EQ(h.object, 0);
  const RayHit down = first_hit(w, {V3(3, 3, 0.5), -V3::UnitZ(), 10});
  ASSERT_TRUE(down.hit);
  EXPECT_EQ(down.object, kSeafloorObject);
  EXPECT_NEAR(down.t, 0.5, 1e-6);
  EXPECT_NEAR(down.normal.z(), 1.0, 1e-9);
  EXPECT_FALSE(first_hit(w, {V3(0, 0, 0.5), V3::UnitX(), 0.9}).hit);  // tmax short of the face
  EXPECT_THROW(first_hit(w, {V3::Zero(), V3(1, 1, 0), 1}), Error);  // not unit
}

TEST(Query, BoxOverlapIsExactAtTheFace) {
  // Unit-ish box of half 0.05 at the origin; query cubes of half 0.01 slid across its +x face.
  const World w(one_object({{Shape{.size = V3(0.1, 0.1, 0.1)}, Pose::Identity()}}));
  OrientedBox q;
  q.half = V3::Constant(0.01);
  for (double x : {0.045, 0.055, 0.0599}) {
    q.centre = V3(x, 0, 0);
    const auto c = surfaces_in_box(w, q);
    ASSERT_FALSE(c.empty()) << x;
    for (const auto& b : c) {
      EXPECT_EQ(b.object, 0);
      EXPECT_NEAR(b.witness.x(), 0.05, 1e-6);  // only the +x face crosses these boxes
      EXPECT_LE((b.witness - q.centre).cwiseAbs().maxCoeff(), 0.01 + 1e-9);
    }
  }
  q.centre = V3(0.0601, 0, 0);
  EXPECT_TRUE(surfaces_in_box(w, q).empty());
  q.centre = V3::Zero();  // wholly inside: no surface crosses it
  EXPECT_TRUE(surfaces_in_box(w, q).empty());
  EXPECT_EQ(inside_objects(w, q.centre), std::vector<int>{0});
  // A thin box rotated 45 deg about z whose corner (0.011 / sqrt 2 from its centre along x)
  // reaches 0.5 mm through the face, then stops 0.5 mm short of it.
  q.rotation = Eigen::AngleAxisd(M_PI / 4, V3::UnitZ()).toRotationMatrix();
  q.half = V3(0.01, 0.001, 0.001);
  q.centre = V3(0.05 + 0.011 / std::sqrt(2.0) - 0.0005, 0, 0);
  EXPECT_FALSE(surfaces_in_box(w, q).empty());
  q.centre.x() += 0.001;
  EXPECT_TRUE(surfaces_in_box(w, q).empty());
}

// The inside test of mesh parts (winding numbers along rays) agrees with the analytic test of
// the same primitive, away from the faceting (1 mm from the surface).
TEST(Query, MeshInsideAgreesWithTheAnalyticPrimitive) {
  const Shape torus{.kind = ShapeKind::torus, .radius = 0.03, .major = 0.1};
  const Pose pose = at(V3(0.2, -0.1, 0.3)) * Pose(Eigen::AngleAxisd(0.7, V3(1, 2, 3).normalized()));
  const World analytic(one_object({{torus, Pose::Identity()}}, pose));
  const Shape file{.kind = ShapeKind::mesh, .file = write_obj(part_mesh({torus, Pose::Identity()}), "torus")};
  const World meshed(one_object({{file, Pose::Identity()}}, pose));
  Rng rng(7);
  int inside = 0, compared = 0;
  for (int i = 0; i < 4000; ++i) {
    const V3 q(rng.uniform() * 0.28 - 0.14, rng.uniform() * 0.28 - 0.14, rng.uniform() * 0.1 - 0.05);
    const double rho = std::hypot(q.x(), q.y()) - 0.1, d = std::hypot(rho, q.z()) - 0.03;
    if (std::abs(d) < 0.001) continue;
    const V3 p = pose * q;
    const bool truth = d < 0;
    ASSERT_EQ(!inside_objects(analytic, p).empty(), truth) << q.transpose();
    ASSERT_EQ(!inside_objects(meshed, p).empty(), truth) << q.transpose();
    inside += truth, ++compared;
  }
  EXPECT_GT(inside, 300);  // the test sampled both sides
  EXPECT_GT(compared - inside, 300);
}

// Two bars crossing with coincident faces (the thesis's cross): every point inside either bar
// is inside the object, including under the crossing where rays meet coincident faces.
TEST(Query, OverlappingMeshPartsWithCoincidentFaces) {
  const Mesh bar = make_box(V3(0.3, 0.03, 0.03));
  const std::string f = write_obj(bar, "bar");
  Pose across = at(V3(0, 0, 0.03));
  across.linear() = Eigen::AngleAxisd(M_PI / 2, V3::UnitZ()).toRotationMatrix();
  const World w(one_object({{Shape{.kind = ShapeKind::mesh, .file = f}, Pose::Identity()},
                            {Shape{.kind = ShapeKind::mesh, .file = f}, across}}));
  Rng rng(3);
  for (int i = 0; i < 2000; ++i) {
    const V3 p(rng.uniform() * 0.06 - 0.03, rng.uniform() * 0.06 - 0.03, rng.uniform() * 0.07 - 0.02);
    const bool in1 = std::abs(p.x()) < 0.15 && std::abs(p.y()) < 0.015 && std::abs(p.z()) < 0.015;
    const bool in2 = std::abs(p.y()) < 0.15 && std::abs(p.x()) < 0.015 && std::abs(p.z() - 0.03) < 0.015;
    const V3 e = p.cwiseAbs();
    if (std::abs(e.y() - 0.015) < 1e-3 || std::abs(e.x() - 0.015) < 1e-3 ||
        std::abs(p.z() - 0.015) < 1e-3 || std::abs(p.z() + 0.015) < 1e-3 || std::abs(p.z() - 0.045) < 1e-3)
      continue;
    ASSERT_EQ(!inside_objects(w, p).empty(), in1 || in2) << p.transpose();
  }
}

TEST(Query, NearestSurfaceOfASphereIsItsRadiusAway) {
  const World w(one_object({{Shape{.kind = ShapeKind::sphere, .radius = 0.05}, Pose::Identity()}}));
  for (const V3& p : {V3(0.2, 0, 0), V3(0.01, 0.02, -0.01), V3(-0.1, 0.1, 0.1)}) {
    const NearestSurface n = nearest_surface(w, p, 1.0);
    ASSERT_EQ(n.object, 0);
    EXPECT_NEAR(n.distance, std::abs(p.norm() - 0.05), 0.05 * 0.01) << p.transpose();  // faceting
    EXPECT_NEAR((n.point - p).norm(), n.distance, 1e-9);
  }
  EXPECT_TRUE(std::isinf(nearest_surface(w, V3(1, 0, 0), 0.5).distance));
}

}  // namespace
