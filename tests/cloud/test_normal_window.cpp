// The normals' window grown for a noisier sensor (organised.hpp, normal_window): the slope error
// it is chosen by against brute force, the frame's noise it measures against the noise put in,
// and the normals it gives on noisy analytic frames against the truth.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "organised_frames.hpp"
#include "shapes.hpp"
#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::cloud {

using namespace organised_test;

// Least-squares planes z = a x + b y + c through (2h+1)^2 pixels of unit spacing with unit depth
// noise: the deviation of a over many draws is the formula's error.
TEST(NormalWindow, SlopeErrorIsTheDeviationOfFittedPlanesSlopes) {
  Rng rng(5);
  for (std::uint32_t h : {1u, 3u, 5u}) {
    const int m = int(2 * h + 1), n = m * m;
    Eigen::MatrixXd A(n, 3);
    for (int i = 0; i < n; ++i) A.row(i) << i % m - int(h), i / m - int(h), 1.0;
    const Eigen::MatrixXd solve = (A.transpose() * A).inverse() * A.transpose();
    double sum2 = 0.0;
    constexpr int kDraws = 4000;
    for (int d = 0; d < kDraws; ++d) {
      Eigen::VectorXd z(n);
      for (int i = 0; i < n; ++i) z[i] = rng.normal();
      const double a = solve.row(0).dot(z);
      sum2 += a * a;
    }
    const double want = normal_slope_error(1.0, h);
    EXPECT_NEAR(std::sqrt(sum2 / kDraws), want, 0.05 * want) << "h " << h;
  }
}

// A 320 x 240 pinhole frame (focal length 500 px, so a pixel's footprint is range / 500) of the
// plane 0.6 y + 0.8 z = 0.8 with noise of `footprints` pixel footprints along each ray, and an
// optional box 0.2 m nearer over the right third (a depth step every sampled row crosses).
Cloud noisy_frame(float footprints, std::uint64_t seed, bool box = false) {
  Rng rng(seed);
  Cloud c;
  c.width = 320, c.height = 240;
  for (std::uint32_t v = 0; v < c.height; ++v)
    for (std::uint32_t u = 0; u < c.width; ++u) {
      const Eigen::Vector3f ray =
          Eigen::Vector3f((u - 160.0f) / 500.0f, (v - 120.0f) / 500.0f, 1.0f).normalized();
      float t = 0.8f / (0.6f * ray.y() + 0.8f * ray.z());
      if (box && u >= 213) t -= 0.2f;
      c.points.push_back(ray * (t + footprints * t / 500.0f * float(rng.normal())));
    }
  return c;
}

double measured(const Cloud& c) {
  WindowScratch scratch;
  return noise_per_pixel(c.points, full_map(c), c.viewpoint, OrganisedConfig{}.depth_change,
                         scratch);
}

TEST(NormalWindow, MeasuresTheNoiseInPixelFootprints) {
  for (float rho : {1.0f, 2.0f, 3.0f}) {
    EXPECT_NEAR(measured(noisy_frame(rho, 2)), rho, 0.08 * rho);
    EXPECT_NEAR(measured(noisy_frame(rho, 3, true)), rho, 0.08 * rho)
        << "a depth step is not noise";
  }
  EXPECT_LT(measured(noisy_frame(0.0f, 2, true)), 0.01);
  Cloud tiny = noisy_frame(2.0f, 2);  // too few triples to measure: no noise measured
  tiny.points.resize(640), tiny.height = 2;
  EXPECT_EQ(measured(tiny), 0.0);
}

std::uint32_t window_of(const Cloud& c, const OrganisedConfig& cfg = {}) {
  return normal_window(measured(c), cfg);
}

TEST(NormalWindow, StaysAtTheConfiguredWindowForTheDefaultSensorAndGrowsForANoisierOne) {
  // The simulated depth camera (1.2 mm + 1.9 mm/m^2 r^2, 1.64 mm pixels at 1 m) is 1.9-2.2
  // footprints along the rays at 0.6-1.4 m; its frames measure 1.5-2.1.
  EXPECT_EQ(window_of(noisy_frame(1.7f, 4)), 3u);
  EXPECT_EQ(window_of(noisy_frame(0.0f, 4)), 3u);  // never below the configured window
  EXPECT_EQ(window_of(noisy_frame(2.6f, 4)), 4u);  // twice its sigma_k: 0.186 rad at 7 x 7
  EXPECT_EQ(window_of(noisy_frame(8.0f, 4)), 4u);  // to max_normal_half_window, 9 x 9
  // Raised, the window grows with the noise. Second differences beyond 3 % of the range are
  // depth steps, so the measure saturates near 7 footprints (where the neighbours' own 1 % rule
  // cuts windows anyway).
  OrganisedConfig wide;
  wide.max_normal_half_window = 7;
  std::uint32_t last = 3;
  for (float rho : {3.0f, 4.0f, 5.0f, 6.0f, 8.0f}) {
    const std::uint32_t h = window_of(noisy_frame(rho, 4), wide);
    EXPECT_GE(h, last) << rho << " footprints";
    last = h;
  }
  EXPECT_GE(last, 6u);
  const double rho = measured(noisy_frame(4.0f, 4));
  const std::uint32_t h = window_of(noisy_frame(4.0f, 4), wide);
  EXPECT_LE(normal_slope_error(rho, h), wide.max_normal_slope);      // the smallest window
  EXPECT_GT(normal_slope_error(rho, h - 1), wide.max_normal_slope);  // within the bound
  OrganisedConfig off;
  off.max_normal_slope = 0.0f;
  EXPECT_EQ(window_of(noisy_frame(8.0f, 4), off), 3u);
}

// Over the pixels 8 or more from the frame's edges (`p` made from a 320 x 240 frame).
double median_error_deg(const Preprocessed& p) {
  const Eigen::Vector3f truth(0.0f, -0.6f, -0.8f);
  std::vector<double> e;
  for (std::uint32_t v = 8; v + 8 < 240; ++v)
    for (std::uint32_t u = 8; u + 8 < 320; ++u)
      if (const std::int32_t j = p.output_of_input[v * 320 + u]; j >= 0)
        e.push_back(test::angle_deg(p.cloud.normals[std::size_t(j)], truth));
  std::nth_element(e.begin(), e.begin() + std::ptrdiff_t(e.size() / 2), e.end());
  return e[e.size() / 2];
}

// The whole organised chain on a frame 2.6 footprints noisy: the grown window's normals are
// nearer the truth than the configured 7 x 7 window's, and at the default sensor's noise the
// chain's normals are the 7 x 7 window's, bit for bit.
TEST(NormalWindow, ThePreprocessedNormalsOfANoisierFrameAreNearerTheTruth) {
  PreprocessConfig cfg;
  cfg.plane.enabled = false, cfg.outliers.enabled = false;
  StageTimer timer;
  PreprocessConfig fixed = cfg;
  fixed.organised.max_normal_slope = 0.0f;
  const Cloud noisy = noisy_frame(2.6f, 6);
  const double grown = median_error_deg(preprocess(noisy, cfg, 1, timer));
  const double seven = median_error_deg(preprocess(noisy, fixed, 1, timer));
  EXPECT_LT(grown, 0.8 * seven) << "grown " << grown << " deg, 7 x 7 " << seven << " deg";
  const Cloud usual = noisy_frame(1.7f, 6);
  const Cloud a = preprocess(usual, cfg, 1, timer).cloud,
              b = preprocess(usual, fixed, 1, timer).cloud;
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.normals.data(), b.normals.data(), a.size() * sizeof(a.normals[0])), 0);
}

}  // namespace uwgrasp::cloud
