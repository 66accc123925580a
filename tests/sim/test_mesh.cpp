// Primitive meshes against their analytic volume and area; mesh files through assimp.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/mesh.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::sim;
constexpr double kPi = std::numbers::pi;

TEST(Mesh, BoxVolumeAreaAndBoundsAreExact) {
  const Mesh m = make_box(Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_NEAR(volume(m), 0.006, 1e-9);  // positive: faces wind outwards
  EXPECT_NEAR(area(m), 2 * (0.02 + 0.03 + 0.06), 1e-7);
  const auto b = bounds(m);
  EXPECT_TRUE(b[1].isApprox(Eigen::Vector3f(0.05f, 0.1f, 0.15f)));
}

TEST(Mesh, CurvedPrimitivesConvergeToTheirAnalyticVolume) {
  // Inscribed polygons lose volume as (1 - sin(2 pi/n)/(2 pi/n)) ~ (2 pi/n)^2 / 6.
  EXPECT_NEAR(volume(make_cylinder(0.05, 0.2, 96)), kPi * 0.0025 * 0.2, 0.003 * kPi * 0.0025 * 0.2);
  EXPECT_NEAR(volume(make_sphere(0.1, 4)), 4.0 / 3.0 * kPi * 1e-3, 0.005 * 4.0 / 3.0 * kPi * 1e-3);
  const double torus = 2 * kPi * kPi * 0.1 * 0.012 * 0.012;
  EXPECT_NEAR(volume(make_torus(0.1, 0.012, 256, 64)), torus, 0.005 * torus);
  EXPECT_NEAR(area(make_plane(2.0, 0.25)), 4.0, 1e-6);
}

TEST(Mesh, TransformMovesEveryVertex) {
  Mesh m = make_box(Eigen::Vector3d::Constant(0.1));
  Pose p = Pose::Identity();
  p.translation() = Eigen::Vector3d(1, 2, 3);
  transform(m, p);
  const auto b = bounds(m);
  EXPECT_TRUE(b[0].isApprox(Eigen::Vector3f(0.95f, 1.95f, 2.95f)));
  EXPECT_NEAR(volume(m), 0.001, 1e-8);  // rigid motion keeps the volume
}

TEST(MeshFile, MissingAndUnparsableFilesAreNamedErrors) {
  EXPECT_THROW(load_mesh("/nonexistent/valve.dae"), Error);
  const auto bad = std::filesystem::temp_directory_path() / "uwgrasp_bad_mesh.obj";
  std::ofstream(bad) << "this is not a mesh\x01\x02";
  try {
    load_mesh(bad.string());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_mesh(bad.string(), -1.0), Error);
}

TEST(MeshFile, EverySharedMeshLoadsWithPlausibleSize) {
  const std::filesystem::path dir = std::filesystem::path(UWGRASP_DATA_DIR) / "meshes";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "shared data not found at " << dir;
  int n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const auto ext = e.path().extension().string();
    if (ext != ".dae" && ext != ".obj") continue;
    const Mesh m = load_mesh(e.path().string());
    const auto b = bounds(m);
    const float size = (b[1] - b[0]).maxCoeff();
    EXPECT_GT(m.triangles.size(), 100u) << e.path();
    EXPECT_GT(size, 0.02f) << e.path();  // metres: 2 cm to 2 m objects
    EXPECT_LT(size, 2.0f) << e.path();
    ++n;
  }
  EXPECT_EQ(n, 9);  // MANIFEST.md: 7 COLLADA files, 2 YCB meshes
}

}  // namespace
