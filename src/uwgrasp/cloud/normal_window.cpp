// The normals' window for a frame's depth noise (organised.hpp, normal_window).
#include <algorithm>
#include <cmath>

#include "uwgrasp/cloud/organised.hpp"

namespace uwgrasp::cloud {

namespace {
constexpr std::uint32_t kRowStep = 8;  // rows sampled
constexpr std::uint32_t kWidest = 7;   // check_window's limit: a 15 x 15 window
constexpr std::size_t kMinSamples = 100;
// Triples whose ranges step by more than 3 times the neighbours' continuity allowance are depth
// edges; within the allowance itself the noise's own tail would be cut off (a sensor twice the
// default's noisy measured 1.2 times the default's, not 1.5).
constexpr float kStepAllowance = 3.0f;

float median(std::vector<float>& v) {
  const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The angle between neighbouring pixels' rays, rad: the median over horizontally adjacent
// in-play pixels of the sampled rows. Depth noise lies along the rays, so it does not move this.
float pixel_pitch(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                  const Eigen::Vector3f& viewpoint, std::vector<float>& angles) {
  angles.clear();
  for (std::uint32_t v = kRowStep / 2; v < map.height; v += kRowStep)
    for (std::uint32_t u = 0; u + 1 < map.width; ++u) {
      const std::size_t p = std::size_t(v) * map.width + u;
      const std::int32_t a = map.slot[p], b = map.slot[p + 1];
      if (a < 0 || b < 0) continue;
      const Eigen::Vector3f ra = points[std::size_t(a)] - viewpoint,
                            rb = points[std::size_t(b)] - viewpoint;
      angles.push_back(std::atan2(ra.cross(rb).norm(), ra.dot(rb)));
    }
  return angles.size() < kMinSamples ? 0.0f : median(angles);
}
}  // namespace

double normal_slope_error(double noise_per_pixel, std::uint32_t h) {
  // A plane fitted to the (2h+1)^2 pixels of a window, spacing s, depth noise sigma: the slope
  // along one axis has the deviation sigma / sqrt(sum x^2), sum x^2 = (2h+1) s^2 h (h+1)(2h+1)/3.
  const double m = 2.0 * h + 1.0;
  return noise_per_pixel / (m * std::sqrt(h * (h + 1.0) / 3.0));
}

double noise_per_pixel(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                       const Eigen::Vector3f& viewpoint, float depth_change,
                       WindowScratch& scratch) {
  std::vector<float>& s = scratch.sample;
  const float pitch = pixel_pitch(points, map, viewpoint, s);
  if (!(pitch > 0.0f)) return 0.0;
  // Along a row of a smooth surface the range's second difference is the noise's (a plane's own
  // bends by hundredths of a millimetre over two pixels): for noise of deviation sigma,
  // independent per pixel, sqrt(6) sigma. Gaps and depth steps (kStepAllowance) do not count.
  s.clear();
  const auto range = [&](std::int32_t k) { return (points[std::size_t(k)] - viewpoint).norm(); };
  for (std::uint32_t v = kRowStep / 2; v < map.height; v += kRowStep)
    for (std::uint32_t u = 1; u + 1 < map.width; ++u) {
      const std::size_t p = std::size_t(v) * map.width + u;
      const std::int32_t a = map.slot[p - 1], b = map.slot[p], c = map.slot[p + 1];
      if (a < 0 || b < 0 || c < 0) continue;
      const float ra = range(a), rb = range(b), rc = range(c),
                  step = kStepAllowance * depth_change * rb;
      if (!(rb > 0.0f) || std::abs(ra - rb) > step || std::abs(rc - rb) > step) continue;
      s.push_back(std::abs(ra - 2.0f * rb + rc) / (pitch * rb));
    }
  if (s.size() < kMinSamples) return 0.0;
  return 1.4826 * double(median(s)) / std::sqrt(6.0);  // the median absolute value's deviation
}

std::uint32_t normal_window(double noise_footprints, const OrganisedConfig& cfg) {
  std::uint32_t h = cfg.normal_half_window;
  if (!(cfg.max_normal_slope > 0.0f)) return h;
  const std::uint32_t widest = std::min(cfg.max_normal_half_window, kWidest);
  while (h < widest && normal_slope_error(noise_footprints, h) > cfg.max_normal_slope) ++h;
  return h;
}

}  // namespace uwgrasp::cloud
