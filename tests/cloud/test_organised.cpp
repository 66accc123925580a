#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>

#include "organised_frames.hpp"
#include "shapes.hpp"
#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace uwgrasp::cloud {

using namespace organised_test;

// Stairs across the frame: plateaus 8 columns wide (wider than the normals' 7 x 7 window), each
// step's rise a share of the range either side of the 1 % continuity allowance (0.95 or 1.05 %,
// alternating by row band), so the windows that hold whole, those a step cuts and those a step
// crosses within the allowance sit next to each other.
Cloud stairs_frame() {
  return frame([](float u, float v) {
    const float rise = int(v) / 8 % 2 ? 1.0105f : 1.0095f;
    return std::pow(rise, std::floor(u / 8.0f));
  });
}

// Each point's normal from the running sums (the windows that hold whole) or its own list
// equals the normal of its listed window pixels: a window a step cuts is never summed whole.
void expect_normals_of_the_lists(const Cloud& c, bool plane_left, bool some_whole = true) {
  std::vector<std::uint32_t> pixels;
  const PixelMap map = full_map(c, &pixels);
  Cloud pts = select(c, pixels);
  OrganisedConfig cfg;
  cfg.half_window = cfg.normal_half_window;  // the normals' window as lists, for brute force
  const Neighbours nb = window_neighbours(pts.points, map, cfg, pts.viewpoint);
  window_normals(pts, map, {});
  std::size_t full = 0;
  for (std::size_t j = 0; j < pts.size(); ++j) {
    // Brute force: the same pixels summed point by point (eq. 4.4-4.7).
    const PointNormal ref = normal_from(pts.points, nb.of(j), pts.points[j], pts.viewpoint);
    // 0.05 degrees: the float angle's resolution near 0 is 0.02 (acos(1 - 6e-8)); a window
    // summed across a step it should stop at turns by degrees.
    EXPECT_LT(test::angle_deg(pts.normals[j], ref.normal), 0.05) << j;
    EXPECT_NEAR(pts.curvature[j], ref.curvature, 1e-5f);
    full += nb.count[j] == nb.k;
    if (plane_left && map.pixel[j] % kW < 40) {  // the plane, facing the camera
      EXPECT_LT(test::angle_deg(pts.normals[j], {0, -0.6f, -0.8f}), 0.05) << j;
    }
  }
  if (some_whole) {
    EXPECT_GT(full, pts.size() / 4);  // the running sums were exercised
  }
  EXPECT_LT(full, pts.size());                      // and the lists
}

TEST(Organised, NormalsFromRunningSumsEqualTheListsAndTheAnalyticPlane) {
  expect_normals_of_the_lists(step_frame(), true);
}

TEST(Organised, NormalsFromRunningSumsEqualTheListsNextToStepsAtTheAllowance) {
  expect_normals_of_the_lists(stairs_frame(), false);
}

// Holes (dropouts, a removed plane) leave pixels out of a window's sums as out of its list:
// windows with holes but no step take the running sums and give the lists' normals.
TEST(Organised, NormalsFromRunningSumsEqualTheListsAroundHoles) {
  Cloud c = step_frame();
  Rng rng(3, 0);
  for (int i = 0; i < 400; ++i) c.points[rng.below(c.size())].x() = std::nanf("");
  expect_normals_of_the_lists(c, true, false);  // few windows are whole: 400 holes in 3,072
}

TEST(Organised, NormalsOnASphereAndTheSameWithOneThread) {
  const Eigen::Vector3f centre(0, 0, 0.6f);
  const Cloud c = frame([&](float u, float v) {  // a 5 cm ball, NaN off it
    const Eigen::Vector3f d = Eigen::Vector3f((u - kW / 2.0f) / kF, (v - kH / 2.0f) / kF, 1).normalized();
    const float b = d.dot(centre), disc = b * b - (centre.squaredNorm() - 0.0025f);
    return disc < 0 ? std::nanf("") : (b - std::sqrt(disc)) * d.z();
  });
  std::vector<std::uint32_t> pixels;
  const PixelMap map = full_map(c, &pixels);
  ASSERT_GT(pixels.size(), 500u);
  Cloud two = select(c, pixels), one = two;
  window_normals(two, map, {});
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    window_normals(one, map, {});
  }
  for (std::size_t j = 0; j < two.size(); ++j) {
    EXPECT_EQ(one.normals[j], two.normals[j]);  // bit for bit
    const Eigen::Vector3f radial = (two.points[j] - centre).normalized();
    // Away from the rim, where a window on a ball seen edge-on is cut and skewed.
    if (radial.dot(-two.points[j].normalized()) > 0.5f) {
      EXPECT_LT(test::angle_deg(two.normals[j], radial), 3.0) << j;
    }
  }
}

TEST(Organised, PreprocessTakesTheOrganisedPathOnlyWhereItCan) {
  const Cloud c = step_frame();
  PreprocessConfig cfg;
  cfg.plane.enabled = false;
  StageTimer t;
  const Preprocessed p = preprocess(c, cfg, 1, t);
  EXPECT_TRUE(p.organised);
  EXPECT_TRUE(p.neighbours.window);
  EXPECT_EQ(path_summary(c, cfg), "organised (64 x 48 frame, 5 x 5 pixel windows)");
  EXPECT_EQ(p.counts.finite, c.size() - 1);
  for (std::size_t i = 0; i < c.size(); ++i)  // the map still points at the same points
    if (p.output_of_input[i] >= 0) {
      EXPECT_EQ(p.cloud.points[std::size_t(p.output_of_input[i])], c.points[i]);
    }
  cfg.voxel.enabled = true;
  EXPECT_FALSE(preprocess(c, cfg, 1, t).organised);
  EXPECT_EQ(path_summary(c, cfg), "k-d tree (the voxel grid is on)");
  cfg.voxel.enabled = false;
  Cloud flat = c;
  make_unorganised(flat);
  EXPECT_FALSE(preprocess(flat, cfg, 1, t).organised);
}

// Frames that cannot take the organised path give a clear error or the k-d tree path, never a
// crash: a layout that does not fit the points, a frame of NaN, a one-row frame, a lone point.
TEST(Organised, BadFramesGiveAnErrorOrTheKdTreePath) {
  PreprocessConfig cfg;
  StageTimer t;
  Cloud c = step_frame();
  c.height = kH + 1;  // width x height says more points than there are
  EXPECT_THROW(
      {
        try {
          preprocess(c, cfg, 1, t);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("width*height"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
  Cloud nan = frame([](float, float) { return std::nanf(""); });
  EXPECT_THROW(preprocess(nan, cfg, 1, t), Error);
  Cloud row = frame([](float, float) { return 1.0f; });
  row.points.resize(kW);  // the first row alone
  row.height = 1;
  const Preprocessed p = preprocess(row, cfg, 1, t);
  EXPECT_FALSE(p.organised);
  EXPECT_EQ(path_summary(row, cfg), "k-d tree (unorganised cloud)");
  Cloud one = frame([](float u, float v) { return u == 3 && v == 3 ? 1.0f : std::nanf(""); });
  EXPECT_THROW(preprocess(one, cfg, 1, t), Error);  // the outlier stage has nothing to judge by
}

// On a frame whose depth noise grows with range as a stereo camera's does (1 mm at 1 m), the
// 7 x 7 window's normals are nearer the true normal than the k-d tree path's 20 nearest.
TEST(Organised, NoisyPlaneNormalsAreNearerTheTruthThanTheKdTreePaths) {
  Cloud c;
  c.width = 320, c.height = 240;
  Rng rng(3);
  const Eigen::Vector3f n(0, -0.6f, -0.8f);  // 0.6 y + 0.8 z = 1
  for (std::uint32_t v = 0; v < c.height; ++v)
    for (std::uint32_t u = 0; u < c.width; ++u) {
      const Eigen::Vector3f d = Eigen::Vector3f((u - 160.0f) / 262.0f, (v - 120.0f) / 262.0f, 1).normalized();
      const float t = 1.0f / (0.6f * d.y() + 0.8f * d.z());
      c.points.push_back(d * (t + 0.001f * t * t * float(rng.normal())));
    }
  PreprocessConfig cfg;
  cfg.plane.enabled = false;
  StageTimer timer;
  const auto median_error = [&](const Preprocessed& p) {
    std::vector<double> e;
    for (const auto& m : p.cloud.normals) e.push_back(test::angle_deg(m, n));
    std::nth_element(e.begin(), e.begin() + std::ptrdiff_t(e.size() / 2), e.end());
    return e[e.size() / 2];
  };
  const double org = median_error(preprocess(c, cfg, 1, timer));
  cfg.organised.enabled = false;
  const double kd = median_error(preprocess(c, cfg, 1, timer));
  EXPECT_LT(org, 5.0);
  EXPECT_LT(org, 0.8 * kd) << "organised " << org << " deg, k-d tree " << kd << " deg";
}

// On a real frame the organised path keeps nearly the points the k-d tree path keeps.
TEST(Organised, RealFrameKeepsThePointsTheKdTreePathKeeps) {
  UWGRASP_DATA_OR_SKIP(path, "clouds/mOSD_learn33.pcd");
  const Cloud in = io::load_cloud(path);
  PreprocessConfig cfg;
  StageTimer t;
  const Preprocessed org = preprocess(in, cfg, 1, t);
  cfg.organised.enabled = false;
  const Preprocessed kd = preprocess(in, cfg, 1, t);
  ASSERT_TRUE(org.organised);
  ASSERT_FALSE(kd.organised);
  std::size_t both = 0;
  for (std::size_t i = 0; i < in.size(); ++i)
    both += org.output_of_input[i] >= 0 && kd.output_of_input[i] >= 0;
  EXPECT_GE(double(both), 0.98 * double(kd.cloud.size()));
  EXPECT_NEAR(double(org.cloud.size()), double(kd.cloud.size()), 0.02 * double(kd.cloud.size()));
  for (const auto& m : org.cloud.normals) ASSERT_NEAR(m.norm(), 1.0f, 1e-4f);
}

}  // namespace uwgrasp::cloud
