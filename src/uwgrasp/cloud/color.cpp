#include "uwgrasp/cloud/color.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

namespace {
void check(const WaterColorConfig& c) {
  for (int i = 0; i < 3; ++i) {
    if (!(c.attenuation[i] >= 0.0) || !std::isfinite(c.attenuation[i]))
      throw Error("preprocess.water.attenuation must be finite and >= 0, got " + std::to_string(c.attenuation[i]));
    if (!(c.veiling[i] >= 0.0 && c.veiling[i] <= 1.0))
      throw Error("preprocess.water.veiling must be in [0, 1], got " + std::to_string(c.veiling[i]));
  }
  if (!(c.min_transmission > 0.0 && c.min_transmission <= 1.0))
    throw Error("preprocess.water.min_transmission must be in (0, 1], got " + std::to_string(c.min_transmission));
}

std::uint8_t to_byte(double v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}
}  // namespace

void restore_colors(Cloud& cloud, const WaterColorConfig& cfg) {
  check(cfg);
  if (!cloud.has_colors()) return;
  const Eigen::Vector3f eye = cloud.viewpoint;
  tbb::parallel_for(std::size_t(0), cloud.size(), [&](std::size_t i) {
    const double d = (cloud.points[i] - eye).norm();
    if (!std::isfinite(d)) return;
    Rgb8& c = cloud.colors[i];
    const double I[3] = {c.r / 255.0, c.g / 255.0, c.b / 255.0};
    std::uint8_t out[3];
    for (int k = 0; k < 3; ++k) {
      const double t = std::max(std::exp(-cfg.attenuation[k] * d), cfg.min_transmission);
      out[k] = to_byte((I[k] - cfg.veiling[k] * (1.0 - t)) / t);
    }
    c = Rgb8{out[0], out[1], out[2]};
  });
}

}  // namespace uwgrasp::cloud
