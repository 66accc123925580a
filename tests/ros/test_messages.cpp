// PointCloud2 <-> the bridge's clouds (C++17, ROS headers): round trips, other layouts, and every
// malformed message an Error naming what is wrong.
#include <gtest/gtest.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <cmath>
#include <cstring>
#include <tuple>

#include "convert.hpp"
#include "messages.hpp"

namespace uwgrasp_ros {
namespace {

PlainCloud grid(std::uint32_t w, std::uint32_t h, bool colours) {
  PlainCloud c;
  c.width = w, c.height = h;
  for (std::uint32_t i = 0; i < w * h; ++i) {
    c.xyz.insert(c.xyz.end(), {0.01f * float(i % w), 0.02f * float(i / w), 1.0f + 0.001f * float(i)});
    if (colours) c.rgb.insert(c.rgb.end(), {std::uint8_t(i), std::uint8_t(2 * i), std::uint8_t(255 - i)});
  }
  c.xyz[4] = std::nanf("");  // a pixel without depth
  return c;
}

TEST(RosMessages, CloudsSurviveTheRoundTrip) {
  for (const bool colours : {false, true}) {
    const PlainCloud c = grid(8, 5, colours);
    const sensor_msgs::PointCloud2 m = to_msg(c);
    EXPECT_EQ(m.width, 8u);
    EXPECT_EQ(m.height, 5u);
    const PlainCloud back = from_msg(m);
    ASSERT_EQ(back.xyz.size(), c.xyz.size());
    for (std::size_t i = 0; i < c.xyz.size(); ++i)
      if (std::isnan(c.xyz[i])) EXPECT_TRUE(std::isnan(back.xyz[i]));
      else EXPECT_EQ(back.xyz[i], c.xyz[i]);
    EXPECT_EQ(back.rgb, c.rgb);
  }
}

// One PlainCloud read into over messages of other sizes, with and without colours (as the node
// does): each read gives exactly what a fresh read gives, and a malformed message leaves it as it
// was.
TEST(RosMessages, ReadingIntoOneCloudGivesWhatAFreshReadGives) {
  PlainCloud reused;
  for (const auto& [w, h, colours] :
       {std::tuple{8u, 5u, true}, std::tuple{3u, 2u, false}, std::tuple{16u, 9u, false},
        std::tuple{4u, 1u, true}, std::tuple{6u, 6u, true}}) {
    const sensor_msgs::PointCloud2 m = to_msg(grid(w, h, colours));
    from_msg(m, reused);
    const PlainCloud fresh = from_msg(m);
    EXPECT_EQ(reused.width, fresh.width);
    EXPECT_EQ(reused.height, fresh.height);
    ASSERT_EQ(reused.xyz.size(), fresh.xyz.size()) << w << " x " << h;
    EXPECT_EQ(std::memcmp(reused.xyz.data(), fresh.xyz.data(), 4 * fresh.xyz.size()),
              0);  // NaN too
    EXPECT_EQ(reused.rgb, fresh.rgb);
    EXPECT_EQ(reused.rgb.empty(), !colours);
  }
  sensor_msgs::PointCloud2 bad = to_msg(grid(2, 2, false));
  bad.fields.erase(bad.fields.begin());
  const PlainCloud before = reused;
  EXPECT_THROW(from_msg(bad, reused), uwgrasp::Error);
  EXPECT_EQ(reused.width, before.width);
  EXPECT_EQ(reused.rgb, before.rgb);
  EXPECT_EQ(std::memcmp(reused.xyz.data(), before.xyz.data(), 4 * before.xyz.size()), 0);
}

// Read straight into a stream's frame (the node's path), a message detects as its PlainCloud
// does; a malformed message leaves the frame as it was.
TEST(RosMessages, ReadingIntoAStreamGivesWhatAPlainCloudGives) {
  const Engine engine("", {});
  Stream stream;
  for (const auto& [w, h, colours] :
       {std::tuple{8u, 5u, true}, std::tuple{3u, 2u, false}, std::tuple{40u, 1u, true}}) {
    const sensor_msgs::PointCloud2 m = to_msg(grid(w, h, colours));
    from_msg(m, stream);
    const PlainDetection got = engine.detect_frame({}, "grid", "t", stream);
    const PlainDetection want = engine.detect(from_msg(m), {}, "grid", "t");
    EXPECT_EQ(got.points_in, std::size_t(w) * h);
    EXPECT_EQ(got.warning, want.warning);
    EXPECT_FALSE(got.warning.empty());  // a grid of points: no object to grasp
    EXPECT_EQ(got.json, want.json);
  }
  sensor_msgs::PointCloud2 bad = to_msg(grid(2, 2, false));
  bad.fields.erase(bad.fields.begin());
  EXPECT_THROW(from_msg(bad, stream), uwgrasp::Error);
  EXPECT_EQ(engine.detect_frame({}, "grid", "t", stream).points_in, 40u);
  sensor_msgs::PointCloud2 behind = to_msg(grid(4, 3, false));  // read, then refused by the engine
  for (std::size_t i = 8; i + 4 <= behind.data.size(); i += behind.point_step) {
    float z;
    std::memcpy(&z, &behind.data[i], 4);
    z = -z;
    std::memcpy(&behind.data[i], &z, 4);
  }
  from_msg(behind, stream);
  EXPECT_THROW(engine.detect_frame({}, "grid", "t", stream), uwgrasp::Error);
}

// FLOAT64 coordinates, padding in each point and at the end of each row: what other drivers send.
TEST(RosMessages, DoublesAndPaddedRowsAreRead) {
  sensor_msgs::PointCloud2 m;
  m.width = 3, m.height = 2, m.point_step = 32, m.row_step = 3 * 32 + 16;
  for (const auto& [name, off] : {std::pair<const char*, std::uint32_t>{"x", 0}, {"y", 8}, {"z", 16}}) {
    sensor_msgs::PointField f;
    f.name = name, f.offset = off, f.datatype = sensor_msgs::PointField::FLOAT64, f.count = 1;
    m.fields.push_back(f);
  }
  m.data.assign(m.row_step * m.height, 0);
  for (std::uint32_t r = 0; r < 2; ++r)
    for (std::uint32_t c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) {
        const double v = 100.0 * r + 10.0 * c + k + 1;
        std::memcpy(&m.data[r * m.row_step + c * m.point_step + 8 * k], &v, 8);
      }
  const PlainCloud p = from_msg(m);
  ASSERT_EQ(p.size(), 6u);
  EXPECT_EQ(p.xyz[3 * 4 + 2], 113.0f);  // row 1, column 1, z
  EXPECT_TRUE(p.rgb.empty());
}

TEST(RosMessages, MalformedCloudsAreErrorsNamingTheProblem) {
  const sensor_msgs::PointCloud2 good = to_msg(grid(4, 3, true));
  const auto expect_error = [](const sensor_msgs::PointCloud2& m, const std::string& word) {
    try {
      from_msg(m);
      ADD_FAILURE() << "no error for " << word;
    } catch (const uwgrasp::Error& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  auto m = good;
  m.fields.erase(m.fields.begin() + 2);
  expect_error(m, "no field 'z'");
  m = good, m.point_step = 8;
  expect_error(m, "point_step");
  m = good, m.data.resize(m.data.size() - 1);
  expect_error(m, "bytes");
  m = good, m.row_step = 4;
  expect_error(m, "row_step");
  m = good, m.width = 0;
  expect_error(m, "empty");
  m = good, m.is_bigendian = true;
  expect_error(m, "big-endian");
  m = good, m.fields[0].datatype = sensor_msgs::PointField::INT16;
  expect_error(m, "not FLOAT32");
  m = good, m.fields[0].datatype = 42;
  expect_error(m, "unknown datatype");
  m = good, m.fields[1].offset = 1u << 31;
  expect_error(m, "past point_step");
  m = good, m.height = 1u << 20, m.width = 1u << 20;  // width x height overflows 32 bits
  expect_error(m, "row_step");
}

TEST(RosMessages, DetectionsBecomeGraspArraysPosesAndMarkers) {
  PlainDetection d;
  d.sampler = "antipodal";
  d.object_xyz = {0, 0, 1, 0.1f, 0, 1};
  for (int i = 0; i < 3; ++i) {
    PlainGrasp g;
    g.pose.p = {0.1 * i, 0, 1};
    g.score = 1.0 - 0.2 * i;
    g.edges.push_back({0, 0, 1, 0, 0.1f, 1});
    d.grasps.push_back(g);
  }
  std_msgs::Header h;
  h.frame_id = "camera_optical";
  const auto arr = grasp_array(d, h);
  ASSERT_EQ(arr.grasps.size(), 3u);
  EXPECT_EQ(arr.grasps[1].rank, 2u);
  EXPECT_EQ(arr.header.frame_id, "camera_optical");
  EXPECT_EQ(pose_array(arr).poses.size(), 3u);
  const auto mk = markers(d, h);
  ASSERT_EQ(mk.markers.size(), 5u);  // DELETEALL, 3 grippers, the object
  EXPECT_EQ(mk.markers[0].action, visualization_msgs::Marker::DELETEALL);
  EXPECT_EQ(mk.markers[3].id, 1);    // the best drawn last
  EXPECT_GT(mk.markers[3].color.g, mk.markers[1].color.g);
  EXPECT_EQ(mk.markers[4].points.size(), 2u);
}

}  // namespace
}  // namespace uwgrasp_ros
