// The depth noise measured on the seafloor (plane_noise.hpp) against floors of known noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "shapes.hpp"
#include "uwgrasp/cloud/plane_noise.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/core/error.hpp"
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

// The plane stage measures twice from one pass of distances and ranges (plane_distances): the
// same law as from the cloud, and lists of two lengths are an error, not a read past one's end.
TEST(PlaneNoise, FromDistancesAndRangesAsFromTheCloud) {
  const Cloud c = noisy_floor(0.0012, 0.0019, 11);
  std::vector<float> distance, range;
  plane_distances(c, kFloor, distance, range);
  ASSERT_EQ(distance.size(), c.size());
  for (const std::size_t i : {std::size_t(0), c.size() / 2, c.size() - 1}) {
    EXPECT_FLOAT_EQ(distance[i], std::abs(kFloor.head<3>().dot(c.points[i]) + kFloor[3]));
    EXPECT_FLOAT_EQ(range[i], (c.points[i] - c.viewpoint).norm());
  }
  NoiseScratch scratch;
  const NoiseModel a = plane_noise(c, kFloor, 0.05f),
                   b = plane_noise(distance, range, 0.05f, kNoiseBin, kNoiseMinPoints, scratch);
  ASSERT_TRUE(a.found);
  EXPECT_EQ(a.sigma0, b.sigma0);
  EXPECT_EQ(a.sigma_k, b.sigma_k);
  EXPECT_EQ(a.bins, b.bins);
  range.pop_back();
  EXPECT_THROW(plane_noise(distance, range, 0.05f, kNoiseBin, kNoiseMinPoints, scratch), Error);
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

namespace uwgrasp::cloud {
// A camera 1 m above a noisy floor (y = 1, optical frame) looking level at a 25 cm wall 1.5 m
// away: depth noise sigma(r) = 7 mm + 1 mm/m^2 r^2 along the ray (6 mm across the floor at the
// wall), so the plane's band (3 sigma) reaches 1.8 cm up the wall's foot. `height` gets each
// pixel's true height above the floor on the wall, -1 off it.
Cloud wall_on_noisy_floor(std::vector<float>& height) {
  constexpr std::uint32_t n = 480;
  constexpr float f = 300.0f;
  Cloud c;
  c.width = c.height = n;
  Rng rng(11);
  for (std::uint32_t v = 0; v < n; ++v)
    for (std::uint32_t u = 0; u < n; ++u) {
      const Eigen::Vector3f d((float(u) - n / 2.0f) / f, (float(v) - n / 2.0f) / f, 1.0f);
      const float wall_y = 1.5f * d.y();  // where the ray meets the wall's plane z = 1.5
      const bool on_wall = wall_y >= 0.75f && wall_y <= 1.0f;
      const float t = on_wall ? 1.5f : (d.y() > 0.0f ? 1.0f / d.y() : 1e9f);
      const float r = t * d.norm();
      height.push_back(on_wall ? 1.0f - wall_y : -1.0f);
      if (r > 6.0f) {
        c.points.emplace_back(std::nanf(""), std::nanf(""), std::nanf(""));
        continue;
      }
      const float sigma = 0.007f + 0.001f * r * r;
      c.points.push_back(d * t * (1.0f + sigma * float(rng.normal()) / r));
    }
  return c;
}

// Plane removal with the normals (4.1.4): in the band the measured noise widens, an object's
// foot (normal across the plane's) stays; without the normals the band takes it.
TEST(Organised, PlaneRemovalWithNormalsKeepsAnObjectsFoot) {
  std::vector<float> height;
  const Cloud c = wall_on_noisy_floor(height);
  PreprocessConfig cfg;
  cfg.outliers.enabled = false;
  std::size_t floor_kept[2] = {0, 0};
  const auto kept_foot = [&](float angle) {
    cfg.plane.normal_angle = angle;
    StageTimer t;
    const Preprocessed p = preprocess(c, cfg, 1, t);
    EXPECT_TRUE(p.plane.found);
    EXPECT_TRUE(p.noise.found);
    std::size_t foot = 0, kept = 0;
    for (std::size_t i = 0; i < c.size(); ++i)
      if (height[i] >= 0.012f && height[i] <= 0.018f) ++foot, kept += !p.plane_of_input[i];
      else if (height[i] < 0.0f && p.output_of_input[i] >= 0) ++floor_kept[angle > 0.0f];
    EXPECT_GT(foot, 300u);
    return double(kept) / double(foot);
  };
  const double with = kept_foot(30.0f), without = kept_foot(0.0f);
  std::printf("wall points 12-18 mm above the floor kept: %.2f with the normals, %.2f without\n", with, without);
  std::printf("floor points left: %zu with the normals, %zu without\n", floor_kept[1], floor_kept[0]);
  EXPECT_GT(with, 0.7);
  EXPECT_LT(without, 0.45);
  // The floor itself stays removed: its normals agree with the plane's.
  EXPECT_LT(double(floor_kept[1]), 1.5 * double(floor_kept[0]) + 100.0);
}
}  // namespace uwgrasp::cloud

namespace uwgrasp::cloud {
namespace {
// The law as first written: a std::map of per-bin lists, std::nth_element for each median.
NoiseModel plane_noise_reference(const Cloud& cloud, const Eigen::Vector4f& plane, float band, double bin) {
  std::map<long, std::vector<double>> bins;
  for (const Eigen::Vector3f& p : cloud.points) {
    const double dist = std::abs(double(plane.head<3>().dot(p) + plane[3]));
    if (dist <= band) bins[std::lround(std::floor((p - cloud.viewpoint).norm() / bin))].push_back(dist);
  }
  Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  NoiseModel m;
  for (auto& [key, v] : bins) {
    if (v.size() < 200) continue;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    const double r = (double(key) + 0.5) * bin, sigma = 1.4826 * v[v.size() / 2];
    const Eigen::Vector2d x(1.0, r * r);
    a += x * x.transpose(), b += x * sigma, ++m.bins;
  }
  if (m.bins < 2 || std::abs(a.determinant()) < 1e-12) return m;
  const Eigen::Vector2d s = a.ldlt().solve(b);
  m.found = true, m.sigma0 = std::max(0.0, s[0]), m.sigma_k = std::max(0.0, s[1]);
  return m;
}
}  // namespace

// The bucketed medians and per-bin lists give the reference's law to the bit, on floors of
// several noises, bands and bin sizes (ties and even-sized bins included: a quantised floor).
TEST(PlaneNoise, SameLawAsTheReferenceImplementation) {
  for (const auto& [s0, sk] : {std::pair{0.001, 0.0}, {0.0012, 0.0019}, {0.006, 0.001}}) {
    Cloud c = noisy_floor(s0, sk, 5);
    for (const float band : {0.005f, 0.03f, 0.1f})
      for (const double bin : {0.1, 0.25}) {
        const NoiseModel a = plane_noise(c, kFloor, band, bin), b = plane_noise_reference(c, kFloor, band, bin);
        ASSERT_EQ(a.found, b.found) << s0 << " " << band;
        EXPECT_EQ(a.bins, b.bins);
        EXPECT_EQ(a.sigma0, b.sigma0) << s0 << " band " << band << " bin " << bin;
        EXPECT_EQ(a.sigma_k, b.sigma_k) << s0 << " band " << band << " bin " << bin;
      }
    for (auto& p : c.points) p.y() = std::round(p.y() * 1000.0f) / 1000.0f;  // millimetre steps: ties
    const NoiseModel a = plane_noise(c, kFloor, 0.03f), b = plane_noise_reference(c, kFloor, 0.03f, 0.25);
    EXPECT_EQ(a.sigma0, b.sigma0);
    EXPECT_EQ(a.sigma_k, b.sigma_k);
  }
  Cloud far = noisy_floor(0.001, 0.0, 2);  // a point a kilometre away: bins by key, not by index
  far.points.emplace_back(0.0f, 1.0f, 1000.0f);
  const NoiseModel a = plane_noise(far, kFloor, 0.03f), b = plane_noise_reference(far, kFloor, 0.03f, 0.25);
  EXPECT_EQ(a.sigma0, b.sigma0);
  EXPECT_EQ(a.sigma_k, b.sigma_k);
}
}  // namespace uwgrasp::cloud
