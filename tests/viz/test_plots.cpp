// viz/ plots: the histogram's bars stand where the values fall, grids place tiles where they
// belong, and the colour bar runs from dark to bright.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <vector>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/viz/picture.hpp"

namespace {

// Fraction of the bar-coloured pixels in the plot column x (the bars' fill colour).
double bar_fill(const cv::Mat& img, int x) {
  int n = 0;
  for (int y = 0; y < img.rows; ++y) n += img.at<cv::Vec3b>(y, x) == cv::Vec3b(160, 110, 50);
  return double(n) / img.rows;
}

TEST(Histogram, BarsStandWhereTheValuesFall) {
  // Four values in the first of 4 bins over [0, 4], eight in the last: the last bar is the
  // tallest (full height), the first half as tall, the middle ones empty.
  std::vector<double> v(4, 0.5);
  v.insert(v.end(), 8, 3.5);
  const cv::Mat img = uwgrasp::viz::histogram(v, 4, 0.0, 4.0, "t", "x");
  // Plot area x in [70, 690): bin b covers 70 + 155 b .. 70 + 155 (b + 1).
  const double first = bar_fill(img, 70 + 77), second = bar_fill(img, 70 + 155 + 77),
               third = bar_fill(img, 70 + 310 + 77), last = bar_fill(img, 70 + 465 + 77);
  EXPECT_GT(last, 0.5);
  EXPECT_NEAR(first, last / 2, 0.01);
  EXPECT_EQ(second, 0.0);
  EXPECT_EQ(third, 0.0);
}

TEST(Histogram, OutOfRangeValuesGoToTheEdgeBinsAndNansAreSkipped) {
  const std::vector<double> v = {-5.0, 100.0, std::nan("")};
  const cv::Mat img = uwgrasp::viz::histogram(v, 2, 0.0, 1.0, "t", "x");
  EXPECT_GT(bar_fill(img, 70 + 155), 0.0);
  EXPECT_GT(bar_fill(img, 70 + 465), 0.0);
  EXPECT_NEAR(bar_fill(img, 70 + 155), bar_fill(img, 70 + 465), 1e-9);
}

TEST(Grid, PlacesTilesRowByRowAndBlanksTheRest) {
  std::vector<cv::Mat> tiles;
  for (int i = 0; i < 3; ++i) tiles.emplace_back(10, 20, CV_8UC3, cv::Scalar(i, i, i));
  const cv::Mat g = uwgrasp::viz::grid(tiles, 2);
  ASSERT_EQ(g.rows, 20);
  ASSERT_EQ(g.cols, 40);
  EXPECT_EQ(g.at<cv::Vec3b>(5, 5), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(g.at<cv::Vec3b>(5, 25), cv::Vec3b(1, 1, 1));
  EXPECT_EQ(g.at<cv::Vec3b>(15, 5), cv::Vec3b(2, 2, 2));
  EXPECT_EQ(g.at<cv::Vec3b>(15, 25), cv::Vec3b(255, 255, 255));
}

TEST(Grid, RejectsMismatchedTiles) {
  std::vector<cv::Mat> tiles = {cv::Mat(10, 20, CV_8UC3), cv::Mat(10, 21, CV_8UC3)};
  EXPECT_THROW(uwgrasp::viz::grid(tiles, 2), uwgrasp::Error);
  EXPECT_THROW(uwgrasp::viz::grid({}, 2), uwgrasp::Error);
}

TEST(ValueColour, RunsFromDarkToBright) {
  const auto brightness = [](cv::Vec3b c) { return int(c[0]) + c[1] + c[2]; };
  EXPECT_LT(brightness(uwgrasp::viz::value_colour(0.0)), brightness(uwgrasp::viz::value_colour(0.5)));
  EXPECT_LT(brightness(uwgrasp::viz::value_colour(0.5)), brightness(uwgrasp::viz::value_colour(1.0)));
  EXPECT_EQ(uwgrasp::viz::value_colour(-3.0), uwgrasp::viz::value_colour(0.0));
  EXPECT_EQ(uwgrasp::viz::value_colour(std::nan("")), uwgrasp::viz::value_colour(0.0));
}

}  // namespace

namespace {

bool has_colour(const cv::Mat& img, cv::Rect r, cv::Vec3b c) {
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x)
      if (img.at<cv::Vec3b>(y, x) == c) return true;
  return false;
}

TEST(LinePlot, LinesRunWhereTheDataLies) {
  // y = x on [0, 1] with the y range fixed to [0, 1]: the line goes from the plot area's
  // bottom-left corner (80, 420) to its top-right (560, 60), and nowhere near the other corners.
  const uwgrasp::viz::Series s{"y=x", {0.0, 1.0}, {0.0, 1.0}};
  uwgrasp::viz::Axes a;
  a.y_lo = 0, a.y_hi = 1;
  const cv::Mat img = uwgrasp::viz::line_plot(std::span(&s, 1), a);
  const cv::Vec3b blue(180, 119, 31);  // the first series' colour
  EXPECT_TRUE(has_colour(img, {318, 238, 5, 5}, blue));   // the middle, (320, 240)
  EXPECT_TRUE(has_colour(img, {82, 412, 6, 6}, blue));    // near the start
  EXPECT_FALSE(has_colour(img, {82, 62, 40, 40}, blue));  // top-left stays empty
  EXPECT_FALSE(has_colour(img, {515, 375, 40, 40}, blue));  // bottom-right too
}

TEST(LinePlot, MismatchedSeriesIsAnError) {
  const uwgrasp::viz::Series s{"bad", {0.0, 1.0}, {0.0}};
  EXPECT_THROW(uwgrasp::viz::line_plot(std::span(&s, 1), {}), uwgrasp::Error);
}

}  // namespace
