#pragma once
// Analytic organised frames for the organised path's tests: a pinhole camera's 64 x 48 crop, a
// tilted plane with a box in front of it, and the map of a frame's valid pixels.
#include <cmath>
#include <cstdint>
#include <vector>

#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::cloud::organised_test {

constexpr std::uint32_t kW = 64, kH = 48;
// A 64 x 48 crop of a camera with a 500-pixel focal length, at the origin.
constexpr float kF = 500.0f;

// A frame seen by the pinhole camera: depth(u, v) gives each pixel's z (NaN: no return).
template <class Depth>
inline Cloud frame(Depth depth) {
  Cloud c;
  c.width = kW, c.height = kH;
  for (std::uint32_t v = 0; v < kH; ++v)
    for (std::uint32_t u = 0; u < kW; ++u) {
      const float z = depth(float(u), float(v));
      c.points.emplace_back((float(u) - kW / 2.0f) * z / kF, (float(v) - kH / 2.0f) * z / kF, z);
    }
  return c;
}

// A tilted plane (normal (0, -0.6, -0.8) towards the camera) with a box 0.2 m nearer in front of
// its right third, and an invalid pixel.
inline Cloud step_frame() {
  return frame([](float u, float v) {
    if (u == 5 && v == 7) return std::nanf("");
    const float plane = 0.8f / (0.8f + 0.6f * (v - kH / 2.0f) / kF);  // 0.6 y + 0.8 z = 0.64
    return u >= 40 ? plane - 0.2f : plane;
  });
}

inline PixelMap full_map(const Cloud& c, std::vector<std::uint32_t>* pixels = nullptr) {
  std::vector<std::uint32_t> p;
  for (std::uint32_t i = 0; i < c.size(); ++i)
    if (is_finite(c.points[i])) p.push_back(i);
  if (pixels) *pixels = p;
  return pixel_map(c.width, c.height, std::move(p));
}

}  // namespace uwgrasp::cloud::organised_test
