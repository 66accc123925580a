// The depth noise measured on the seafloor (plane_noise.hpp) against floors of known noise.
#include <gtest/gtest.h>

#include "shapes.hpp"
#include "uwgrasp/cloud/plane_noise.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::cloud {

namespace {
// A floor 1 m below the camera (y down) from 0.5 to 4 m ahead, each point displaced along the
// floor's normal by sigma0 + sigma_k r^2, and a 10 cm box on it 1.5 m ahead.
Cloud noisy_floor(double sigma0, double sigma_k, std::uint64_t seed) {
  Rng rng(seed, 0);
  Cloud c;
  for (float x = -1; x <= 1; x += 0.01f)
    for (float z = 0.5f; z <= 4; z += 0.01f) {
      const double r = Eigen::Vector3f(x, 1, z).norm();
      c.points.emplace_back(x, 1.0f + float((sigma0 + sigma_k * r * r) * rng.normal()), z);
    }
  test::append(c, test::box_surface({-0.05f, 0.9f, 1.45f}, {0.05f, 0.999f, 1.55f}, 0.004f));
  make_unorganised(c);
  return c;
}

const Eigen::Vector4f kFloor(0, -1, 0, 1);  // -y + 1 = 0, the camera on the positive side
}  // namespace

TEST(PlaneNoise, RecoversTheNoiseLawOfAFloor) {
  for (const auto& [s0, sk] : {std::pair{0.001, 0.0}, {0.0012, 0.0019}, {0.003, 0.001}}) {
    const NoiseModel m = plane_noise(noisy_floor(s0, sk, 7), kFloor, 0.1f);
    ASSERT_TRUE(m.found);
    EXPECT_GE(m.bins, 10);
    for (const double r : {1.2, 2.0, 3.5})  // within 10 % of the truth where the floor is seen
      EXPECT_NEAR(m.at(r), s0 + sk * r * r, 0.1 * (s0 + sk * r * r)) << "sigma0 " << s0 << " r " << r;
  }
}

TEST(PlaneNoise, NotFoundWithoutASpanOfRanges) {
  Cloud c;
  for (float x = -1; x <= 1; x += 0.01f) c.points.emplace_back(x, 1.0f, 2.0f);  // one range bin
  EXPECT_FALSE(plane_noise(c, kFloor, 0.1f).found);
  EXPECT_FALSE(plane_noise(Cloud{}, kFloor, 0.1f).found);
}

TEST(PlaneNoise, TheInlierBandFollowsTheMeasuredNoise) {
  // 6 mm + 1 mm/m^2: beyond 1 cm of the plane lie ~10 % of the floor's points at 1 m, more far.
  const Cloud c = noisy_floor(0.006, 0.001, 3);
  const std::size_t box = c.size() - 351 * 201;  // the points appended after the floor
  StageTimer t;
  PreprocessConfig fixed;
  fixed.plane.noise_sigmas = 0.0f;
  fixed.outliers.enabled = false;
  PreprocessConfig adaptive = fixed;
  adaptive.plane.noise_sigmas = 3.0f;
  const Preprocessed a = preprocess(c, fixed, 1, t), b = preprocess(c, adaptive, 1, t);
  EXPECT_FALSE(a.noise.found);
  ASSERT_TRUE(b.noise.found);
  EXPECT_NEAR(b.noise.at(2.0), 0.010, 0.0015);
  // The fixed band leaves thousands of floor points as "objects"; three sigma leaves < 1 %.
  EXPECT_GT(a.cloud.size(), box + 5000);
  EXPECT_LT(b.cloud.size(), box + 351 * 201 / 100);
  // The box's top and sides survive but their lowest ~3 cm (3 sigma at 1.8 m) and the bottom face,
  // which lies in the floor: about 65 % of its points.
  std::size_t top = 0;
  for (const auto& p : b.cloud.points) top += p.y() < 0.91f;
  EXPECT_GT(top, box / 8);
  EXPECT_GT(b.cloud.size(), box * 55 / 100);
}

}  // namespace uwgrasp::cloud
