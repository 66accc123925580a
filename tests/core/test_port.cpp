// The flat port (core/port.hpp) against Snell's law worked by hand: the angle in water, where
// the ray leaves the glass, and the inverse (the in-air direction that sees a water point).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/port.hpp"

namespace {
using namespace uwgrasp;
using V3 = Eigen::Vector3d;

FlatPort acrylic() { return FlatPort{0.02, 0.012, 1.0, 1.49, 1.34}; }

TEST(Port, TheWaterAngleObeysSnellAcrossBothFaces) {
  const FlatPort port = acrylic();
  for (const double deg : {0.0, 5.0, 20.0, 35.0, 50.0, 70.0}) {
    const double a = deg * std::numbers::pi / 180.0;
    const auto out = refract_through_port(port, V3(std::sin(a), 0.0, std::cos(a)));
    ASSERT_TRUE(out) << deg;
    // n_air sin(a) = n_glass sin(g) = n_water sin(w): the glass drops out of the water angle.
    const double w = std::atan2(out->direction.x(), out->direction.z());
    EXPECT_NEAR(std::sin(w), port.n_air * std::sin(a) / port.n_water, 1e-12) << deg;
    EXPECT_NEAR(out->direction.z(), 1.0, 1e-12);
    const double g = std::asin(port.n_air * std::sin(a) / port.n_glass);
    EXPECT_NEAR(out->origin.z(), port.distance + port.thickness, 1e-12);
    EXPECT_NEAR(out->origin.x(), port.distance * std::tan(a) + port.thickness * std::tan(g), 1e-12) << deg;
    EXPECT_NEAR(out->origin.y(), 0.0, 1e-15);
  }
}

TEST(Port, TheInverseFindsTheRayThatSeesAWaterPoint) {
  const FlatPort port = acrylic();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> xy(-0.7, 0.7);
  for (int i = 0; i < 200; ++i) {
    const V3 d(xy(rng), xy(rng), 1.0);
    const auto out = refract_through_port(port, d);
    ASSERT_TRUE(out);
    const V3 p = out->origin + (0.3 + 3.0 * std::abs(xy(rng))) * out->direction;
    const auto back = direction_to(port, p);
    ASSERT_TRUE(back);
    EXPECT_NEAR((*back - d).norm(), 0.0, 1e-9) << d.transpose();
  }
  // On the axis, and not beyond the port.
  EXPECT_NEAR((*direction_to(port, V3(0, 0, 1)) - V3(0, 0, 1)).norm(), 0.0, 1e-15);
  EXPECT_FALSE(direction_to(port, V3(0.1, 0, 0.025)));
}

TEST(Port, TotalReflectionAndBadPortsAreRefused) {
  // Into an optically thinner medium past the critical angle there is no refracted ray.
  EXPECT_FALSE(refract(V3(std::sin(1.2), 0, std::cos(1.2)), V3(0, 0, -1), 1.5, 1.0));
  EXPECT_TRUE(refract(V3(std::sin(0.5), 0, std::cos(0.5)), V3(0, 0, -1), 1.5, 1.0));
  EXPECT_FALSE(refract_through_port(acrylic(), V3(1, 0, 0)));
  for (const auto& bad : {FlatPort{-0.01, 0.01, 1, 1.5, 1.33}, FlatPort{0.01, NAN, 1, 1.5, 1.33},
                          FlatPort{0.01, 0.01, 1, 0.5, 1.33}, FlatPort{0.01, 0.01, 1, 1.5, 4.0}})
    EXPECT_THROW(check_port(bad), Error);
  EXPECT_NO_THROW(check_port(acrylic()));
}

}  // namespace
