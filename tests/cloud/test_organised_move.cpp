// Points moved along their rays onto quadratics fitted to their windows' ranges (organised.hpp,
// move_onto_quadrics): the whole window's weights against the least-squares fit they stand for;
// on analytic frames (a plane, a ball, a thin rod, a depth step) the moved points against the
// true surfaces, the noise the moves report against the noise put in, and the whole chain's
// choice of when to move.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <vector>

#include "organised_frames.hpp"
#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::cloud {

using namespace organised_test;

namespace {
constexpr std::uint32_t kWide = 320, kTall = 240;
constexpr float kFocal = 500.0f;

Eigen::Vector3f ray_of(std::uint32_t u, std::uint32_t v) {
  return Eigen::Vector3f((float(u) - 160.0f) / kFocal, (float(v) - 120.0f) / kFocal, 1.0f)
      .normalized();
}

// A 320 x 240 pinhole frame (focal length 500 px): hit(ray) is the true range along a pixel's
// ray (nullopt: no return), and the measured range errs by sigma0 + sigma_k r^2 (the simulated
// depth camera's law).
Cloud noisy(const std::function<std::optional<float>(const Eigen::Vector3f&)>& hit, float sigma0,
            float sigma_k, std::uint64_t seed) {
  Rng rng(seed);
  Cloud c;
  c.width = kWide, c.height = kTall;
  for (std::uint32_t v = 0; v < kTall; ++v)
    for (std::uint32_t u = 0; u < kWide; ++u) {
      const Eigen::Vector3f ray = ray_of(u, v);
      const std::optional<float> t = hit(ray);
      if (!t) {
        c.points.emplace_back(std::nanf(""), std::nanf(""), std::nanf(""));
        continue;
      }
      c.points.push_back(ray * (*t + (sigma0 + sigma_k * *t * *t) * float(rng.normal())));
    }
  return c;
}

// The plane 0.6 y + 0.8 z = 0.8 (about 1 m ahead), and a box face 0.2 m nearer over the right
// third when `step`.
std::optional<float> plane(const Eigen::Vector3f& ray, bool step, std::uint32_t u) {
  const float t = 0.8f / (0.6f * ray.y() + 0.8f * ray.z());
  return step && u >= 213 ? t - 0.2f : t;
}

// A ball of radius 0.1 m 0.8 m ahead, before a wall 1.5 m ahead.
constexpr float kRadius = 0.1f;
const Eigen::Vector3f kCentre(0.0f, 0.0f, 0.8f);
std::optional<float> ball(const Eigen::Vector3f& ray) {
  const float b = ray.dot(kCentre), disc = b * b - (kCentre.squaredNorm() - kRadius * kRadius);
  if (disc < 0.0f) return 1.5f / ray.z();
  return b - std::sqrt(disc);
}

// The cloud of the frame's valid pixels with its map, moved over 9 x 9 windows.
struct Moved {
  Cloud cloud;
  PixelMap map;
  std::vector<std::uint32_t> pixels;
  MovedOntoQuadrics noise;
};

Moved move(const Cloud& frame, bool apply = true) {
  Moved m;
  std::vector<std::uint32_t> valid;
  for (std::uint32_t i = 0; i < frame.size(); ++i)
    if (is_finite(frame.points[i])) valid.push_back(i);
  m.pixels = valid;
  for (const std::uint32_t i : valid) m.cloud.points.push_back(frame.points[i]);
  m.map = pixel_map(frame.width, frame.height, valid);
  OrganisedConfig cfg;
  cfg.normal_half_window = 4;
  WindowScratch scratch;
  if (apply) m.noise = move_onto_quadrics(m.cloud, m.map, cfg, scratch);
  return m;
}

// The RMS of err(point, pixel) over the pixels 10 or more from the frame's edges that keep(pixel).
template <class Err, class Keep>
double rms(const Moved& m, Err err, Keep keep) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t j = 0; j < m.cloud.size(); ++j) {
    const std::uint32_t p = m.pixels[j], u = p % kWide, v = p / kWide;
    if (u < 10 || v < 10 || u + 10 >= kWide || v + 10 >= kTall || !keep(u, v)) continue;
    const double e = err(m.cloud.points[j], u, v);
    sum += e * e, ++n;
  }
  return n ? std::sqrt(sum / double(n)) : 0.0;
}
}  // namespace

// The whole window's weights are the least-squares quadratic's value at the centre: they sum to
// one, reproduce any quadratic (and no odd or cross term leaks in), and their squares sum to
// alpha, checked against a 6 x 6 least-squares solve over the same window.
TEST(MoveOntoQuadrics, TheWholeWindowsWeightsAreTheLeastSquaresFit) {
  for (std::uint32_t h = 1; h <= 7; ++h) {
    const QuadraticKernel k = quadratic_kernel(h);
    const int n = int(h);
    Eigen::Matrix<double, 6, 6> ata = Eigen::Matrix<double, 6, 6>::Zero();
    double sum = 0.0, squares = 0.0, quadratic = 0.0;
    for (int dv = -n; dv <= n; ++dv)
      for (int du = -n; du <= n; ++du) {
        const double w = k.alpha + k.beta * (du * du + dv * dv);
        sum += w, squares += w * w;
        quadratic +=
            w * (0.3 + 0.7 * du - 1.1 * dv + 0.05 * du * du - 0.2 * du * dv + 0.4 * dv * dv);
        Eigen::Matrix<double, 6, 1> a;
        a << 1.0, du, dv, du * du, du * dv, dv * dv;
        ata += a * a.transpose();
      }
    EXPECT_NEAR(sum, 1.0, 1e-12) << h;
    EXPECT_NEAR(quadratic, 0.3, 1e-12) << h;
    EXPECT_NEAR(squares, k.alpha, 1e-12) << h;
    // The least-squares centre value's variance factor: the (0, 0) entry of (A^T A)^-1.
    EXPECT_NEAR(ata.inverse()(0, 0), k.alpha, 1e-12) << h;
  }
  EXPECT_NEAR(std::sqrt(quadratic_kernel(4).alpha), 0.2107, 1e-4);  // 9 x 9
}

// A plane 1 pixel footprint noisy (2 mm at 1 m), its windows whole: the moved points lie
// sqrt(alpha) = 0.21 of the noise from it (a 9 x 9 window's fit), and the moves report the noise
// put in and the noise left. At 3 footprints (6 mm at 1 m) the continuity test cuts a quarter
// of the nearest ring from each window (two pixels' noise differs by more than the 1 %
// allowance), and keeps the pixels nearer the point's own range: the fit leans towards the
// point, the moves read 0.85 of the noise and leave 0.29 of it.
TEST(MoveOntoQuadrics, APlanesPointsMoveOntoItAndTheMovesMeasureTheNoise) {
  const auto hit = [](const Eigen::Vector3f& r) { return plane(r, false, 0); };
  const auto off = [](const Eigen::Vector3f& p, std::uint32_t, std::uint32_t) {
    return double(0.6f * p.y() + 0.8f * p.z() - 0.8f);
  };
  const auto all = [](std::uint32_t, std::uint32_t) { return true; };
  const double left = std::sqrt(quadratic_kernel(4).alpha);
  for (const float sigma_k : {0.002f, 0.006f}) {
    const Cloud frame = noisy(hit, 0.0f, sigma_k, 3);
    const double before = rms(move(frame, false), off, all);
    const Moved m = move(frame);
    const double after = rms(m, off, all);
    if (sigma_k < 0.004f) {
      EXPECT_NEAR(after / before, left, 0.15 * left) << before << " -> " << after << " m";
      EXPECT_NEAR(m.noise.noise, sigma_k, 0.1 * sigma_k);
      EXPECT_NEAR(m.noise.left, left * sigma_k, 0.1 * left * sigma_k);
    } else {
      EXPECT_LT(after / before, 0.35) << before << " -> " << after << " m";
      EXPECT_NEAR(m.noise.noise, 0.85 * sigma_k, 0.1 * sigma_k);
    }
  }
  // A noiseless plane stays where it is and reports no noise.
  const Moved exact = move(noisy(hit, 0.0f, 0.0f, 3));
  EXPECT_LT(rms(exact, off, all), 2e-6);
  EXPECT_LT(exact.noise.noise, 1e-5);
}

// A ball 0.1 m across at 0.8 m, as noisy: its points move nearer the sphere.
TEST(MoveOntoQuadrics, ABallsPointsMoveNearerTheSphere) {
  const Cloud frame = noisy(ball, 0.0f, 0.006f, 5);
  const auto off = [](const Eigen::Vector3f& p, std::uint32_t, std::uint32_t) {
    return double((p - kCentre).norm() - kRadius);
  };
  // The ball's pixels whose ray meets it 45 degrees or more from grazing (the limb's windows
  // reach over the edge to the wall).
  const auto face = [](std::uint32_t u, std::uint32_t v) {
    const Eigen::Vector3f r = ray_of(u, v);
    const std::optional<float> t = ball(r);
    if (std::abs(*t * r.z() - 1.5f) < 1e-4f) return false;
    const Eigen::Vector3f n = (r * *t - kCentre).normalized();
    return -n.dot(r) > 0.7071f;
  };
  const double before = rms(move(frame, false), off, face);
  const double after = rms(move(frame), off, face);
  EXPECT_LT(after, before / 3.0) << before << " -> " << after << " m";
}

// A rod 2 cm across at 0.6 m (a handle, a bar), before a wall: a 9 x 9 window spans half its
// width, and a plane fitted over it would sit (window extent)^2 / (6 R) = 0.4 mm inside the
// surface at the crest. The quadratic follows the bend: noiseless, the rod's points near its
// crest stay on it to a tenth of that (the circle's fourth-order term is what is left);
// noisy, they move nearer it with no bias.
TEST(MoveOntoQuadrics, ARodsPointsStayOnItsCurve) {
  constexpr float kRod = 0.01f, kAhead = 0.6f;
  // The rod along x through (0, 0, kAhead): where a ray meets the circle y^2 + (z - kAhead)^2.
  const auto rod = [](const Eigen::Vector3f& r) -> std::optional<float> {
    const float a = r.y() * r.y() + r.z() * r.z(), b = r.z() * kAhead,
                disc = b * b - a * (kAhead * kAhead - kRod * kRod);
    if (disc < 0.0f) return 1.5f / r.z();
    return (b - std::sqrt(disc)) / a;
  };
  const auto off = [](const Eigen::Vector3f& p, std::uint32_t, std::uint32_t) {
    return double(std::hypot(p.y(), p.z() - kAhead) - kRod);
  };
  // The rod's pixels whose ray meets it 45 degrees or more from grazing, 6 mm of its crest.
  const auto face = [&](std::uint32_t u, std::uint32_t v) {
    const Eigen::Vector3f r = ray_of(u, v);
    const Eigen::Vector3f p = r * *rod(r);
    return std::abs(p.z() - 1.5f) > 0.1f && std::abs(p.y()) < 0.006f;
  };
  const Moved exact = move(noisy(rod, 0.0f, 0.0f, 11));
  EXPECT_LT(rms(exact, off, face), 6e-5);
  const Cloud frame = noisy(rod, 0.0f, 0.006f, 11);
  const Moved raw = move(frame, false), m = move(frame);
  const double before = rms(raw, off, face), after = rms(m, off, face);
  EXPECT_LT(after, before / 2.5) << before << " -> " << after << " m";
  double bias = 0.0;
  std::size_t n = 0;
  for (std::size_t j = 0; j < m.cloud.size(); ++j) {
    const std::uint32_t u = m.pixels[j] % kWide, v = m.pixels[j] / kWide;
    if (u >= 10 && u + 10 < kWide && face(u, v)) bias += off(m.cloud.points[j], u, v), ++n;
  }
  ASSERT_GT(n, 1000u);
  EXPECT_LT(std::abs(bias / double(n)), 1e-4) << "mean signed distance, m";
}

// A box face 0.2 m in front of the plane: no window joins the two sides, so no point lands in
// the gap between them, and more than 3 pixels from the step the moves take out most of the
// noise. The windows the step cuts fit their quadratics on one side of the point, which leaves
// the columns next to the step noisier than a whole window would (bounded here).
TEST(MoveOntoQuadrics, ADepthStepIsLeftIntact) {
  const auto hit = [](const Eigen::Vector3f& r) {
    const int u = int(std::lround(r.x() / r.z() * kFocal + 160.0f));
    return plane(r, true, std::uint32_t(u));
  };
  const Cloud frame = noisy(hit, 0.0f, 0.006f, 7);
  const Moved raw = move(frame, false), m = move(frame);
  std::size_t in_gap = 0;
  constexpr std::uint32_t kFirst = 203, kColumns = 20;  // 10 pixels each side of the step
  std::array<double, kColumns> before{}, after{};
  for (std::size_t j = 0; j < m.cloud.size(); ++j) {
    const std::uint32_t u = m.pixels[j] % kWide;
    const Eigen::Vector3f r = ray_of(u, m.pixels[j] / kWide);
    const float range = m.cloud.points[j].norm(), want = *plane(r, true, u);
    const float far = *plane(r, false, u), near = far - 0.2f;
    // 5 sigma of the noise at 1.3 m from either surface (the raw points stay within it)
    if (range > near + 0.05f && range < far - 0.05f) ++in_gap;
    if (u >= kFirst && u < kFirst + kColumns) {
      before[u - kFirst] += std::pow(double(raw.cloud.points[j].norm() - want), 2.0);
      after[u - kFirst] += std::pow(double(range - want), 2.0);
    }
  }
  EXPECT_EQ(in_gap, 0u);
  for (std::uint32_t i = 0; i < kColumns; ++i) {
    const std::uint32_t u = kFirst + i;
    const double ratio = std::sqrt(after[i] / before[i]);  // RMS after over RMS before
    if (u + 3 < 213 || u > 215)
      EXPECT_LT(ratio, 0.35) << "column " << u << " (the step between 212 and 213)";
    else
      EXPECT_LT(ratio, 1.5) << "column " << u << ", its window cut by the step";
  }
}

// Through the organised chain: a frame at the simulated camera's noise keeps 7 x 7 and is not
// moved (the points bit for bit as without the move); one at four times its sigma_k gets 9 x 9,
// is moved, and reports the error left: sqrt(alpha) of the noise the moves read (0.6-1 of the
// noise put in: the continuity test keeps the pixels nearer a point's own range).
TEST(MoveOntoQuadrics, TheChainMovesOnlyTheFramesWhoseWindowGrew) {
  PreprocessConfig cfg;
  cfg.plane.enabled = false, cfg.outliers.enabled = false;
  PreprocessConfig off = cfg;
  off.organised.move_onto_quadrics = false;
  StageTimer timer;
  const auto hit = [](const Eigen::Vector3f& r) { return plane(r, false, 0); };
  const Cloud usual = noisy(hit, 0.0012f, 0.0019f, 9);
  const Preprocessed a = preprocess(usual, cfg, 1, timer), b = preprocess(usual, off, 1, timer);
  EXPECT_EQ(a.normal_half_window, 3u);
  EXPECT_EQ(a.moved_depth_error, 0.0);
  ASSERT_EQ(a.cloud.size(), b.cloud.size());
  EXPECT_EQ(std::memcmp(a.cloud.points.data(), b.cloud.points.data(),
                        a.cloud.size() * sizeof(a.cloud.points[0])),
            0);
  const Cloud noisier = noisy(hit, 0.0f, 0.008f, 9);
  const Preprocessed c = preprocess(noisier, cfg, 1, timer), d = preprocess(noisier, off, 1, timer);
  EXPECT_EQ(c.normal_half_window, 4u);
  const double left = 0.008 * std::sqrt(quadratic_kernel(4).alpha);
  EXPECT_GT(c.moved_depth_error, 0.6 * left);
  EXPECT_LT(c.moved_depth_error, left);
  EXPECT_EQ(d.moved_depth_error, 0.0);
  EXPECT_NE(normals_summary(c).find("moved onto their windows' range fits"), std::string::npos);
}

}  // namespace uwgrasp::cloud
