#include <gtest/gtest.h>

#include "shapes.hpp"
#include "uwgrasp/io/pcd.hpp"
#include "uwgrasp/segment/pipeline.hpp"

namespace uwgrasp::segment {

TEST(Pipeline, MugOnTableIsOneSegmentAfterTheTableIsRemoved) {
  UWGRASP_DATA_OR_SKIP(path, "clouds/table_scene_mug_stereo_textured.pcd");
  const Cloud in = io::load_cloud(path);
  const Scene s = segment_scene(in, {}, {}, 1);
  ASSERT_TRUE(s.pre.plane.found);
  EXPECT_GT(s.pre.counts.plane, 100000u);  // the table
  // The mug stands about 0.75 m from the camera; everything else is the far background.
  std::vector<std::size_t> near;
  for (std::size_t i = 0; i < s.info.size(); ++i)
    if (s.info[i].centroid.z() < 1.0f && s.info[i].points >= 1000) near.push_back(i);
  ASSERT_EQ(near.size(), 1u) << "the mug must be one segment";
  const auto& mug = s.info[near[0]];
  EXPECT_GT(mug.points, 10000u);
  // Extent of a mug: about 10 cm wide.
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9f), hi = -lo;
  for (auto i : s.segmentation.segments[near[0]])
    lo = lo.cwiseMin(s.pre.cloud.points[i]), hi = hi.cwiseMax(s.pre.cloud.points[i]);
  EXPECT_LT((hi - lo).maxCoeff(), 0.2f);
  EXPECT_GT((hi - lo).maxCoeff(), 0.05f);
  // No remaining point of the mug segment lies on the table plane.
  for (auto i : s.segmentation.segments[near[0]]) {
    const auto& m = s.pre.plane.coefficients;
    EXPECT_GT(std::abs(m.head<3>().dot(s.pre.cloud.points[i]) + m[3]), 0.009f);
  }
  const auto lab = input_labels(s);
  EXPECT_EQ(lab.size(), in.size());
}

TEST(Pipeline, RecordsEveryStage) {
  Cloud c = test::plane_grid(80, 2.0f, 2.0f);
  test::append(c, test::sphere(2000, 0.1f, {0, 0, 1.8f}));
  const Scene s = segment_scene(c, {}, {}, 1);
  std::vector<std::string> names;
  for (const auto& st : s.timer.stages()) names.push_back(st.name);
  EXPECT_EQ(names, (std::vector<std::string>{"finite", "range", "plane", "outliers", "normals",
                                             "segment"}));
  EXPECT_EQ(s.info.size(), s.segmentation.segments.size());
}

}  // namespace uwgrasp::segment
