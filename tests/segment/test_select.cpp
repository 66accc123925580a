#include <gtest/gtest.h>

#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/segment/select.hpp"

namespace uwgrasp::segment {

namespace {
std::vector<SegmentInfo> three() {
  std::vector<SegmentInfo> v(3);
  v[0].points = 500, v[0].intensity = 0.3f, v[0].distance = 2.0f;
  v[1].points = 100, v[1].intensity = 0.8f, v[1].distance = 3.0f;
  v[2].points = 300, v[2].intensity = 0.1f, v[2].distance = 1.0f;
  for (auto& s : v) s.extent = 0.1f;
  return v;
}
}  // namespace

TEST(Select, ColourIntensity) {
  EXPECT_FLOAT_EQ(color_intensity({255, 0, 0}, "red"), 1.0f);
  EXPECT_FLOAT_EQ(color_intensity({128, 128, 128}, "red"), 0.0f);
  EXPECT_FLOAT_EQ(color_intensity({0, 255, 0}, "red"), 0.0f);
  EXPECT_FLOAT_EQ(color_intensity({255, 255, 0}, "yellow"), 1.0f);
  EXPECT_FLOAT_EQ(color_intensity({255, 255, 0}, "red"), 0.0f);  // yellow is not red
  EXPECT_NEAR(color_intensity({200, 100, 50}, "red"), 100 / 255.0f, 1e-6f);
  EXPECT_NEAR(color_intensity({200, 180, 40}, "yellow"), 140 / 255.0f, 1e-6f);
  EXPECT_THROW(color_intensity({1, 2, 3}, "mauve"), Error);
}

TEST(Select, EachCriterion) {
  const auto v = three();
  ObjectConfig c;
  EXPECT_EQ(select_object(v, c), 1u);  // highest intensity of red (thesis 7.4.2)
  c.by = ObjectBy::largest;
  EXPECT_EQ(select_object(v, c), 0u);
  c.by = ObjectBy::nearest;
  EXPECT_EQ(select_object(v, c), 2u);
  c.by = ObjectBy::label, c.label = 2;
  EXPECT_EQ(select_object(v, c), 2u);
  c.label = 3;
  EXPECT_THROW(select_object(v, c), Error);
}

// A fragment no wider than min_extent - marine snow near the lens, many points and the nearest
// centroid - is never what nearest, largest or point pick, but colour and label may name it.
TEST(Select, GeometricCriteriaPassOverFragments) {
  auto v = three();
  v.emplace_back();
  v[3].points = 900, v[3].intensity = 0.9f, v[3].distance = 0.3f, v[3].extent = 0.008f;
  v[3].centroid = {0.0f, 0.0f, 0.3f};
  ObjectConfig c;
  EXPECT_EQ(select_object(v, c), 3u);  // the reddest
  c.by = ObjectBy::largest;
  EXPECT_EQ(select_object(v, c), 0u);
  c.by = ObjectBy::nearest;
  EXPECT_EQ(select_object(v, c), 2u);
  c.by = ObjectBy::point, c.point = Eigen::Vector3d(0, 0, 0.3);
  EXPECT_NE(select_object(v, c), 3u);
  c.by = ObjectBy::label, c.label = 3;
  EXPECT_EQ(select_object(v, c), 3u);
  c.by = ObjectBy::nearest, c.min_extent = 0.0f;
  EXPECT_EQ(select_object(v, c), 3u);
  c.min_extent = 0.2f;  // nothing is that wide
  try {
    (void)select_object(v, c);
    ADD_FAILURE() << "a fragment selected";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("min_extent"), std::string::npos) << e.what();
  }
}

TEST(Select, NothingRedEnoughIsAnError) {
  auto v = three();
  for (auto& s : v) s.intensity = 0.05f;
  EXPECT_THROW(select_object(v, {}), Error);
  EXPECT_THROW(select_object({}, {}), Error);
}

TEST(Select, DescribeSegments) {
  Cloud c;
  c.points = {{0, 0, 1}, {0, 0, 3}, {5, 5, 5}};
  c.colors = {{255, 0, 0}, {255, 0, 0}, {0, 0, 255}};
  make_unorganised(c);
  Segmentation s;
  s.label = {0, 0, 1};
  s.segments = {{0, 1}, {2}};
  const auto info = describe_segments(c, s, "red");
  ASSERT_EQ(info.size(), 2u);
  EXPECT_EQ(info[0].points, 2u);
  EXPECT_FLOAT_EQ(info[0].centroid.z(), 2.0f);
  EXPECT_FLOAT_EQ(info[0].distance, 2.0f);
  EXPECT_FLOAT_EQ(info[0].intensity, 1.0f);
  EXPECT_FLOAT_EQ(info[1].intensity, 0.0f);
  EXPECT_FLOAT_EQ(info[0].extent, 2.0f);
  EXPECT_FLOAT_EQ(info[1].extent, 0.0f);
  EXPECT_EQ(info[1].mean_color, (Rgb8{0, 0, 255}));
}

}  // namespace uwgrasp::segment
