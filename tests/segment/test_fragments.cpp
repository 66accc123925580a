// Fragments are not objects (select.hpp, extent_of): a dense speck near the lens (marine snow)
// has the scene's nearest centroid and may have more points than the object; a geometric
// criterion passes over it, and it never joins the object picked as a part.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "shapes.hpp"
#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/segment/objects.hpp"

namespace uwgrasp::segment {

namespace {
struct Scene {
  Cloud cloud;
  Objects objects;
  std::size_t box = 0, speck = 0, near_speck = 0;  // object indices
};

// A 6 cm box 1 m away (1,536 points); a 7 mm speck of 2,000 points 0.3 m from the camera; another 3
// cm from the box's side, within part_reach of it. All red.
Scene scene() {
  Scene s;
  s.cloud = test::box_surface({0, 0, 1}, {0.06f, 0.06f, 1.06f}, 0.004f);
  const std::size_t box = s.cloud.size();
  test::append(s.cloud, test::sphere(2000, 0.0035f, {0.03f, 0.03f, 0.3f}));
  const std::size_t speck = s.cloud.size();
  test::append(s.cloud, test::sphere(1500, 0.0035f, {0.09f, 0.03f, 1.03f}));
  test::paint(s.cloud, {220, 20, 20});
  const cloud::KdTree tree(s.cloud.points);
  const auto nb = cloud::knn_all(tree, s.cloud.points, 16);
  s.objects = connected_objects(s.cloud, nb, 0.012f, 10);
  const auto of = [&](std::size_t i) { return std::size_t(s.objects.object_of_point[i]); };
  s.box = of(0), s.speck = of(box), s.near_speck = of(speck);
  return s;
}
}  // namespace

TEST(Fragments, GeometricCriteriaPickTheBoxNotTheSpeck) {
  const Scene s = scene();
  ASSERT_EQ(s.objects.points.size(), 3u);
  ASSERT_LT(s.objects.points[s.box].size(), s.objects.points[s.speck].size());
  EXPECT_NEAR(extent_of(s.cloud, s.objects.points[s.speck]), 0.007f * std::sqrt(3.0f), 0.001f);
  EXPECT_NEAR(extent_of(s.cloud, s.objects.points[s.box]), 0.06f * std::sqrt(3.0f), 0.001f);
  ObjectConfig cfg;
  for (const ObjectBy by : {ObjectBy::nearest, ObjectBy::largest, ObjectBy::point}) {
    cfg.by = by, cfg.point = Eigen::Vector3d(0.03, 0.03, 0.3);  // on the speck
    EXPECT_EQ(select_whole_object(s.cloud, s.objects, Segmentation{}, cfg), s.box) << int(by);
    // The speck beside the box is not one of its parts either.
    EXPECT_EQ(gather_parts(s.cloud, s.objects, s.box, cfg, cfg.part_reach), std::vector{s.box});
  }
  // Without the threshold, the old answers: the speck is nearest and largest.
  cfg.min_extent = 0.0f;
  cfg.by = ObjectBy::nearest;
  EXPECT_EQ(select_whole_object(s.cloud, s.objects, Segmentation{}, cfg), s.speck);
  cfg.by = ObjectBy::largest;
  EXPECT_NE(select_whole_object(s.cloud, s.objects, Segmentation{}, cfg), s.box);
}

TEST(Fragments, ColourAndLabelStillNameWhatTheySay) {
  const Scene s = scene();
  ObjectConfig cfg;  // by colour: a red speck beside the red box is its part
  EXPECT_EQ(gather_parts(s.cloud, s.objects, s.box, cfg, cfg.part_reach).size(), 2u);
  Segmentation seg;
  seg.segments = {{s.objects.points[s.speck].front()}};
  cfg.by = ObjectBy::label, cfg.label = 0;
  EXPECT_EQ(select_whole_object(s.cloud, s.objects, seg, cfg), s.speck);
}

TEST(Fragments, OnlyFragmentsIsAnErrorNamingTheKey) {
  Cloud c = test::sphere(2000, 0.0035f, {0.03f, 0.03f, 0.3f});
  const cloud::KdTree tree(c.points);
  const Objects o = connected_objects(c, cloud::knn_all(tree, c.points, 16), 0.012f, 10);
  ObjectConfig cfg;
  cfg.by = ObjectBy::nearest;
  try {
    (void)select_whole_object(c, o, Segmentation{}, cfg);
    ADD_FAILURE() << "a speck selected";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("segment.object.min_extent"), std::string::npos)
        << e.what();
  }
}

}  // namespace uwgrasp::segment
