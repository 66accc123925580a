// Colour restoration inverts the simulator's water (an independent implementation of the same
// formation law, sim/water.cpp): colours seen through water come back to within the 8-bit
// quantisation amplified by 1/t, and red that water made grey is red again.
#include <gtest/gtest.h>

#include <random>

#include "uwgrasp/cloud/color.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/water.hpp"

namespace uwgrasp::cloud {
namespace {

WaterColorConfig from(const sim::WaterConfig& w) {
  WaterColorConfig c;
  c.enabled = true;
  c.attenuation = w.attenuation;
  c.veiling = w.veiling;
  return c;
}

std::uint8_t byte(double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); }

TEST(RestoreColors, InvertsTheWaterOfEveryPreset) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0), range(0.3, 2.5);
  for (const char* name : {"clear", "coastal", "turbid"}) {
    const sim::WaterConfig w = sim::water_preset(name);
    Cloud c;
    std::vector<Eigen::Vector3d> truth;
    for (int i = 0; i < 500; ++i) {
      const Eigen::Vector3d J(u(rng), u(rng), u(rng));
      const Eigen::Vector3f dir = Eigen::Vector3f(float(u(rng) - 0.5), float(u(rng) - 0.5), 1.0f).normalized();
      const double d = range(rng);
      const Eigen::Vector3d I = sim::underwater_color(J, d, w);
      c.points.push_back(dir * float(d));
      c.colors.push_back(Rgb8{byte(I.x()), byte(I.y()), byte(I.z())});
      truth.push_back(J);
    }
    make_unorganised(c);
    restore_colors(c, from(w));
    for (std::size_t i = 0; i < truth.size(); ++i) {
      const double d = c.points[i].norm();
      for (int k = 0; k < 3; ++k) {
        const double t = std::exp(-w.attenuation[k] * d);
        if (t < WaterColorConfig{}.min_transmission) continue;  // clamped: noise, not colour
        const double got = (k == 0 ? c.colors[i].r : k == 1 ? c.colors[i].g : c.colors[i].b) / 255.0;
        ASSERT_NEAR(got, truth[i][k], 0.5 / 255 / t + 0.5 / 255 + 1e-9) << name << " point " << i << " channel " << k;
      }
    }
  }
}

TEST(RestoreColors, RedComesBackInTurbidWater) {
  const sim::WaterConfig w = sim::water_preset("turbid");
  const Eigen::Vector3d red(0.8, 0.1, 0.1), seen = sim::underwater_color(red, 1.5, w);
  ASSERT_LT(seen.x(), seen.y());  // through 1.5 m of turbid water the red barbell looks green-grey
  Cloud c;
  c.points = {Eigen::Vector3f(0, 0, 1.5f)};
  c.colors = {Rgb8{byte(seen.x()), byte(seen.y()), byte(seen.z())}};
  make_unorganised(c);
  restore_colors(c, from(w));
  EXPECT_GT(c.colors[0].r, 3 * c.colors[0].g);
}

TEST(RestoreColors, PreprocessingRunsItOnlyWhenEnabled) {
  Cloud c;
  for (int i = 0; i < 50; ++i) {
    c.points.push_back(Eigen::Vector3f(0.01f * i, 0.0f, 1.0f));
    c.colors.push_back(Rgb8{40, 120, 110});
  }
  make_unorganised(c);
  PreprocessConfig pre;
  pre.plane.enabled = false;
  pre.outliers.enabled = false;
  StageTimer t1, t2;
  const Preprocessed off = preprocess(c, pre, 1, t1);
  EXPECT_EQ(off.cloud.colors[0], (Rgb8{40, 120, 110}));
  pre.water = from(sim::water_preset("coastal"));
  const Preprocessed on = preprocess(c, pre, 1, t2);
  EXPECT_GT(on.cloud.colors[0].r, 40);
  EXPECT_GT(t2.ms("color"), 0.0);
}

TEST(RestoreColors, BadCoefficientsAreErrors) {
  Cloud c;
  WaterColorConfig w;
  w.attenuation.x() = -1;
  EXPECT_THROW(restore_colors(c, w), Error);
  w = WaterColorConfig{};
  w.veiling.z() = 1.5;
  EXPECT_THROW(restore_colors(c, w), Error);
  w = WaterColorConfig{};
  w.min_transmission = 0;
  EXPECT_THROW(restore_colors(c, w), Error);
}

}  // namespace
}  // namespace uwgrasp::cloud
