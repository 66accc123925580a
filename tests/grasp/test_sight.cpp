// What one view saw (grasp/sight.hpp): the depth seen along a ray, from the view's map of bins,
// against a brute force over the scene's points - the nearest in the ray's bin, else in the
// 3 x 3 bins around it, else the seafloor.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "uwgrasp/grasp/sight.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::grasp;
using V3 = Eigen::Vector3f;
constexpr float kInf = std::numeric_limits<float>::infinity();

float brute_depth(const std::vector<V3>& scene, const std::optional<Eigen::Vector4f>& floor,
                  float resolution, float x, float y) {
  const float inverse = 1.0f / resolution;
  const int u = sight_detail::bin_of(x, inverse), v = sight_detail::bin_of(y, inverse);
  float own = kInf, around = kInf;
  for (const V3& p : scene) {
    if (!(p.z() > 0.0f)) continue;
    const int pu = sight_detail::bin_of(p.x() / p.z(), inverse),
              pv = sight_detail::bin_of(p.y() / p.z(), inverse);
    if (pu == u && pv == v) own = std::min(own, p.z());
    if (std::abs(pu - u) <= 1 && std::abs(pv - v) <= 1) around = std::min(around, p.z());
  }
  if (own < kInf) return own;
  if (around < kInf || !floor) return around;
  const float den = floor->head<3>().dot(V3(x, y, 1.0f));
  if (std::abs(den) > 1e-6f && -(*floor)[3] / den > 0.0f) return -(*floor)[3] / den;
  return kInf;
}

// A camera-frame scene: a sparse, speckled cloud over part of the view with a rectangle
// removed (the seafloor the plane stage took out), a few points behind the camera.
std::vector<V3> scene_points(std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<V3> out;
  for (int i = 0; i < 1500; ++i) {
    const float x = unit(rng) * 0.8f - 0.4f, y = unit(rng) * 0.6f - 0.3f;
    if (x > 0.0f && x < 0.2f && y > -0.1f && y < 0.1f) continue;
    const float z = 0.5f + 1.5f * unit(rng);
    out.emplace_back(x * z, y * z, z);
  }
  out.emplace_back(0.1f, 0.1f, -1.0f);
  out.emplace_back(0.0f, 0.0f, 0.0f);
  return out;
}

TEST(Sight, SeenDepthIsTheNearestInTheBinOrAroundItOrTheSeafloor) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const std::vector<V3> scene = scene_points(rng);
  const std::vector<V3> object{V3(1.0f, 0.0f, 0.0f)};
  // The seafloor 1.2 m below a camera pitched down, and no seafloor.
  for (const std::optional<Eigen::Vector4f>& floor :
       {std::optional<Eigen::Vector4f>(Eigen::Vector4f(0.0f, -0.8f, -0.6f, 1.2f)),
        std::optional<Eigen::Vector4f>()}) {
    for (const float resolution : {0.003f, 0.011f, 0.05f}) {
      const SceneView view =
          make_scene_view(scene, floor, Pose::Identity(), resolution, object, 0.003f);
      int empty_bins = 0;
      for (int q = 0; q < 4000; ++q) {
        // Over the view and past its edges.
        const float x = unit(rng) * 1.2f - 0.6f, y = unit(rng) * 1.0f - 0.5f;
        const float expected = brute_depth(scene, floor, resolution, x, y);
        ASSERT_EQ(sight_detail::seen_depth(view, x, y), expected)
            << "resolution " << resolution << " at " << x << ", " << y;
        empty_bins += brute_depth(scene, std::nullopt, resolution, x, y) == kInf;
      }
      EXPECT_GT(empty_bins, 200);  // the rays through the hole and past the edges were asked
    }
  }
}

TEST(Sight, AnEmptySceneSeesOnlyTheSeafloor) {
  const Eigen::Vector4f floor(0.0f, -1.0f, 0.0f, 1.0f);
  const SceneView view =
      make_scene_view({}, floor, Pose::Identity(), 0.003f, std::vector<V3>{V3::Zero()}, 0.003f);
  EXPECT_FLOAT_EQ(sight_detail::seen_depth(view, 0.0f, 0.5f), 2.0f);  // -d / (n . (x, y, 1))
  EXPECT_EQ(sight_detail::seen_depth(view, 0.0f, -0.5f), kInf);       // above the horizon
}

}  // namespace
