// The same scene and seed render the same frame on every machine with AVX2, whatever Embree's
// kernels the CPU would pick (world.cpp caps them at AVX2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "uwgrasp/sim/render.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::sim;

// FNV-1a over the bits of every point's x, y and z, pixel by pixel (a dropped pixel as NaN).
std::uint64_t points_hash(const Cloud& c) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const Eigen::Vector3f& p : c.points)
    for (int k = 0; k < 3; ++k) {
      std::uint32_t bits = 0x7fc00000u;  // one NaN for every dropped pixel
      if (std::isfinite(p[k])) std::memcpy(&bits, &p[k], sizeof bits);
      for (int b = 0; b < 4; ++b) h = (h ^ ((bits >> (8 * b)) & 0xffu)) * 0x100000001b3ULL;
    }
  return h;
}

// The thesis scene without sensor noise: Embree's hits and our geometry make its points (the
// same hash with glibc's FMA maths switched off, GLIBC_TUNABLES=glibc.cpu.hwcaps=-FMA,-AVX2).
// On an AVX-512 machine without the cap the hash differs (`simulate`'s noiseless thesis frame:
// 27,251 points moved by up to 0.5 um). The constant is this frame's on AVX2 and AVX-512
// machines; a change to the renderer that moves a point changes it: check that the change is
// meant (the other Render tests), then record the new value.
TEST(Reproducible, TheThesisFrameIsTheSameOnEveryMachine) {
  const Scene s = builtin_scene("thesis");
  const World world(s);
  RenderConfig c;
  c.noise.enabled = false;
  const Frame f = render_rgbd(world, camera_pose(s, Mount{}), c, 3);
  ASSERT_EQ(f.cloud.size(), 640u * 480u);
  std::size_t finite = 0;
  for (const auto& p : f.cloud.points) finite += std::isfinite(p.z());
  EXPECT_GT(finite, f.cloud.size() / 2);  // the scene fills the view
  EXPECT_EQ(points_hash(f.cloud), 0xef2cc1bd35fcbc37ULL) << std::hex << points_hash(f.cloud);
}

}  // namespace
