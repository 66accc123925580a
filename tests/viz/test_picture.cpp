// viz/ pictures: the title, legend and colour bar stay legible where the cloud fills the frame
// with points as bright as the text (a near view of a grasp on a light object).
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "uwgrasp/viz/picture.hpp"

namespace {

using namespace uwgrasp;

// A white wall of points filling the view, and one wire to bring up the colour bar.
Cloud white_wall() {
  Cloud c;
  for (int i = -150; i <= 150; ++i)
    for (int j = -150; j <= 150; ++j) {
      c.points.emplace_back(0.004f * float(i), 0.004f * float(j), 1.0f);
      c.colors.push_back({255, 255, 255});
    }
  return c;
}

// The median grey level of img inside r.
double median_grey(const cv::Mat& img, cv::Rect r) {
  cv::Mat grey;
  cv::cvtColor(img(r), grey, cv::COLOR_BGR2GRAY);
  std::vector<std::uint8_t> v(grey.begin<std::uint8_t>(), grey.end<std::uint8_t>());
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

TEST(Picture, TextStandsOnADarkPanelOverBrightPoints) {
  const Cloud wall = white_wall();
  std::vector<viz::Wire> wires(2);
  wires[0].segments.push_back({Eigen::Vector3f(-0.1f, 0, 0.9f), Eigen::Vector3f(0.1f, 0, 0.9f)});
  wires[1] = wires[0], wires[1].value = 1.0;
  viz::Picture pic;
  pic.title = "a title as long as a scene's name: top 10 grasps";
  pic.legend = {"a legend line under it", "and another"};
  viz::View view;
  view.azimuth = view.elevation = 0.0;
  view.distance = 1.0;  // 0.84 m of the wall across the frame, a point every 6 pixels
  pic.point_size = 8;
  const cv::Mat img = viz::draw(wall, wires, pic, view);
  // The wall is white wherever nothing is drawn over it...
  EXPECT_GT(median_grey(img, cv::Rect(500, 400, 200, 100)), 240.0);
  // ...and dark behind the header (three text lines, top left) and the colour bar's labels
  // (right), where the text is light: mostly panel, a few strokes.
  EXPECT_LT(median_grey(img, cv::Rect(8, 8, 300, 70)), 100.0);
  EXPECT_LT(median_grey(img, cv::Rect(img.cols - 95, img.rows / 5 - 45, 20, 40)), 100.0);
}

}  // namespace
