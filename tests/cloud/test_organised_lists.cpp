// The organised path's window lists and outlier statistic against brute force on analytic
// frames (organised.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "organised_frames.hpp"
#include "shapes.hpp"
#include "uwgrasp/cloud/outliers.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::cloud {

using namespace organised_test;

TEST(Organised, WindowListsAreSymmetricAndStopAtDepthSteps) {
  const Cloud c = step_frame();
  std::vector<std::uint32_t> pixels;
  const PixelMap map = full_map(c, &pixels);
  const Cloud pts = select(c, pixels);
  const Neighbours nb = window_neighbours(pts.points, map, {}, pts.viewpoint);
  ASSERT_TRUE(nb.window);
  ASSERT_EQ(nb.k, 25u);
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t j = 0; j < pts.size(); ++j) {
    const auto row = nb.of(j);
    ASSERT_GE(row.size(), 1u);
    EXPECT_EQ(row[0], j);  // the point itself first
    const std::uint32_t u = map.pixel[j] % kW;
    for (const auto q : row) {
      edges.insert({std::uint32_t(j), q});
      EXPECT_EQ(u >= 40, map.pixel[q] % kW >= 40) << "a neighbour across the 0.5 m step";
      const int du = int(map.pixel[q] % kW) - int(u), dv = int(map.pixel[q] / kW) - int(map.pixel[j] / kW);
      EXPECT_LE(std::max(std::abs(du), std::abs(dv)), 2);
    }
    // An interior pixel away from the step and the hole has its whole window.
    const std::uint32_t v = map.pixel[j] / kW;
    if (u >= 2 && u + 2 < 40 && v >= 2 && v + 2 < kH && !(u >= 3 && u <= 7 && v >= 5 && v <= 9)) {
      EXPECT_EQ(row.size(), 25u) << "pixel " << u << ", " << v;
    }
  }
  for (const auto& [a, b] : edges) EXPECT_TRUE(edges.count({b, a})) << a << " -> " << b;
}

// Every point's list is, in order, itself and then the continuous in-play pixels of its window
// ring by ring (row-major within a ring), as a brute force over the pixels lists them: at the
// frame's borders (bounds tested pixel by pixel), inside it (the window's offset table), next to
// holes and across the step, at two window sizes.
TEST(Organised, WindowListsAreTheContinuousPixelsRingByRingAsABruteForceListsThem) {
  Cloud c = step_frame();
  Rng rng(7, 0);
  for (int i = 0; i < 300; ++i) c.points[rng.below(c.size())].x() = std::nanf("");  // holes
  std::vector<std::uint32_t> pixels;
  const PixelMap map = full_map(c, &pixels);
  const Cloud pts = select(c, pixels);
  for (const std::uint32_t h : {2u, 4u}) {
    OrganisedConfig cfg;
    cfg.half_window = h;
    const Neighbours nb = window_neighbours(pts.points, map, cfg, pts.viewpoint);
    for (std::size_t j = 0; j < pts.size(); ++j) {
      const int u = int(map.pixel[j] % kW), v = int(map.pixel[j] / kW);
      const float rj = pts.points[j].norm();
      std::vector<std::uint32_t> want{std::uint32_t(j)};
      for (int ring = 1; ring <= int(h); ++ring)
        for (int dv = -ring; dv <= ring; ++dv)
          for (int du = -ring; du <= ring; ++du) {
            if (std::max(std::abs(du), std::abs(dv)) != ring) continue;
            if (u + du < 0 || u + du >= int(kW) || v + dv < 0 || v + dv >= int(kH)) continue;
            const std::int32_t s = map.slot[std::size_t((v + dv) * int(kW) + u + du)];
            if (s < 0) continue;
            const float rs = pts.points[std::size_t(s)].norm();
            if (std::abs(rs - rj) <= cfg.depth_change * float(ring) * 0.5f * (rs + rj)) want.push_back(std::uint32_t(s));
          }
      const auto row = nb.of(j);
      ASSERT_EQ(std::vector<std::uint32_t>(row.begin(), row.end()), want) << "pixel " << u << ", " << v << ", h " << h;
      for (std::size_t e = 0; e < row.size(); ++e)
        EXPECT_EQ(nb.dists_of(j)[e], (pts.points[row[e]] - pts.points[j]).squaredNorm());
    }
  }
}

TEST(Organised, MeanDistancesAreTheWindowsKNearestByBruteForce) {
  Cloud c = test::plane_grid(30, 0.3f, 1.0f, 7, 0.004f);  // 30 x 30 noisy grid as a frame
  c.width = c.height = 30;
  c.points[100] = Eigen::Vector3f(0.0f, 0.0f, 1.5f);  // a flying pixel
  std::vector<std::uint32_t> pixels;
  const PixelMap map = full_map(c, &pixels);
  const std::vector<float> mean = window_mean_distances(c.points, map, 2, 10);
  for (std::size_t j = 0; j < c.size(); ++j) {
    std::vector<float> d;
    const int u = int(j % 30), v = int(j / 30);
    // The 5 x 5 window, wider (to 13 x 13) while it holds fewer than 10: a corner's has 8.
    for (int h = 2; h <= 6 && (h == 2 || d.size() < 10); ++h) {
      d.clear();
      for (int dv = -h; dv <= h; ++dv)
        for (int du = -h; du <= h; ++du)
          if ((du || dv) && u + du >= 0 && u + du < 30 && v + dv >= 0 && v + dv < 30)
            d.push_back((c.points[std::size_t((v + dv) * 30 + u + du)] - c.points[j]).norm());
    }
    std::sort(d.begin(), d.end());
    double sum = 0;
    const std::size_t k = std::min<std::size_t>(10, d.size());
    for (std::size_t e = 0; e < k; ++e) sum += d[e];
    EXPECT_NEAR(mean[j], sum / double(k), 1e-5) << j;
  }
  EXPECT_GT(mean[100], 20 * mean[500]);
}

// The same against a brute force where many distances tie (a grid of whole millimetres), with
// holes, at three window sizes and k from 1 to more than a window holds: the k smallest are
// chosen by rank (a whole 5 x 5 window) or by insertion (a window that must grow) alike.
TEST(Organised, MeanDistancesWithTiesHolesAndAnyKAreTheBruteForces) {
  constexpr int kSide = 24;
  Cloud c;
  c.width = c.height = kSide;
  Rng rng(11, 0);
  for (int v = 0; v < kSide; ++v)
    for (int u = 0; u < kSide; ++u)
      c.points.emplace_back(0.001f * float(u), 0.001f * float(v),
                            1.0f + 0.001f * float(rng.below(3)));
  for (int i = 0; i < 150; ++i) c.points[rng.below(c.size())].x() = std::nanf("");
  std::vector<std::uint32_t> pixels;
  const PixelMap map = full_map(c, &pixels);
  const Cloud pts = select(c, pixels);
  for (const std::uint32_t h : {1u, 2u, 3u})
    for (const std::uint32_t k : {1u, 5u, 10u, 24u, 60u}) {
      const std::vector<float> mean = window_mean_distances(pts.points, map, h, k);
      for (std::size_t j = 0; j < pts.size(); ++j) {
        const int u = int(map.pixel[j] % kSide), v = int(map.pixel[j] / kSide);
        std::vector<float> d;
        for (int w = int(h); w <= 3 * int(h) && (w == int(h) || d.size() < k); ++w) {
          d.clear();
          for (int dv = -w; dv <= w; ++dv)
            for (int du = -w; du <= w; ++du)
              if ((du || dv) && u + du >= 0 && u + du < kSide && v + dv >= 0 && v + dv < kSide)
                if (const auto s = map.slot[std::size_t((v + dv) * kSide + u + du)]; s >= 0)
                  d.push_back((pts.points[std::size_t(s)] - pts.points[j]).norm());
        }
        std::sort(d.begin(), d.end());
        const std::size_t n = std::min<std::size_t>(k, d.size());
        double sum = 0;
        for (std::size_t e = 0; e < n; ++e) sum += d[e];
        if (n == 0) EXPECT_TRUE(std::isinf(mean[j])) << j;
        else
          EXPECT_NEAR(mean[j], sum / double(n), 1e-7)
              << "h " << h << ", k " << k << ", point " << j;
      }
    }
}

// A pixel with no other pixel in play within the widest window (13 x 13) is a flying pixel:
// its statistic is infinity, it is removed, and it is left out of the statistic's mean and
// deviation, so flying pixels do not widen the threshold for the rest (a k-d tree search finds
// their neighbours however far, and a few of them widen it: on a simulated frame from 4.5 to
// 16 mm). Here three such pixels change nothing else the window statistic removes, and make the
// k-d tree path keep more of the plane.
TEST(Organised, FlyingPixelsAreRemovedWithoutWideningTheThreshold) {
  Cloud c = test::plane_grid(30, 0.3f, 1.0f, 7, 0.004f);
  c.width = c.height = 30;
  std::vector<std::uint32_t> block;  // rows 0-14, and three pixels 7-13 rings from the rest
  for (std::uint32_t i = 0; i < 15 * 30; ++i) block.push_back(i);
  std::vector<std::uint32_t> all = block;
  for (const std::uint32_t i : {22u * 30 + 27, 27u * 30 + 5, 27u * 30 + 20}) all.push_back(i);
  c.points[22 * 30 + 27].z() -= 0.5f;  // half a metre in front of the plane
  const OutlierConfig cfg{true, 10, 1.0f};
  const auto removed_by_window = [&](const std::vector<std::uint32_t>& pixels) {
    const Cloud pts = select(c, pixels);
    return remove_outliers_by(pts, cfg, window_mean_distances(pts.points, pixel_map(30, 30, pixels), 2, 10)).indices;
  };
  const std::vector<std::uint32_t> kept_block = removed_by_window(block), kept_all = removed_by_window(all);
  EXPECT_LT(kept_block.size(), block.size());  // the noise alone removes some of the plane
  EXPECT_EQ(kept_all, kept_block);             // the same ones, and the three flying pixels
  const auto kd_kept = [&](const std::vector<std::uint32_t>& pixels) {
    return remove_outliers(select(c, pixels), cfg).indices.size();
  };
  EXPECT_GT(kd_kept(all), kd_kept(block));
}

}  // namespace uwgrasp::cloud
