// Plots and image conversion for PNG output.
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/viz/image_files.hpp"
#include "uwgrasp/viz/picture.hpp"
#include "uwgrasp/viz/plot_text.hpp"

namespace uwgrasp::viz {

using detail::kInk;
using detail::text;

cv::Vec3b value_colour(double t) {
  static const cv::Mat lut = [] {
    cv::Mat ramp(1, 256, CV_8U), out;
    for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(i);
    cv::applyColorMap(ramp, out, cv::COLORMAP_VIRIDIS);
    return out;
  }();
  const int i = std::clamp(static_cast<int>(std::lround((std::isfinite(t) ? t : 0.0) * 255)), 0, 255);
  return lut.at<cv::Vec3b>(0, i);
}

cv::Vec3b label_colour(std::uint32_t label) {
  if (label == 0) return {110, 110, 110};
  // Golden-ratio hue steps keep neighbouring labels apart.
  const double h = std::fmod(label * 0.618033988749895, 1.0) * 180.0;
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(h, 200, 240)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  return bgr.at<cv::Vec3b>(0, 0);
}

cv::Mat histogram(std::span<const double> values, int bins, double lo, double hi,
                  const std::string& title, const std::string& xlabel) {
  bins = std::max(bins, 1);
  if (lo == hi && !values.empty()) {
    const auto [a, b] = std::minmax_element(values.begin(), values.end());
    lo = *a, hi = *b > *a ? *b : *a + 1.0;
  }
  if (!(hi > lo)) hi = lo + 1.0;
  std::vector<int> count(bins, 0);
  for (const double v : values)
    if (std::isfinite(v)) ++count[std::clamp(int((v - lo) / (hi - lo) * bins), 0, bins - 1)];
  // A multiple of 4 so the four count ticks are whole numbers.
  const int top = (std::max(1, *std::max_element(count.begin(), count.end())) + 3) / 4 * 4;
  cv::Mat img(480, 720, CV_8UC3, cv::Scalar(255, 255, 255));
  const int x0 = 70, x1 = 690, y0 = 420, y1 = 60;
  const double w = double(x1 - x0) / bins;
  for (int b = 0; b < bins; ++b) {
    const int h = int(double(count[b]) / top * (y0 - y1));
    cv::rectangle(img, cv::Point(int(x0 + b * w) + 1, y0 - h), cv::Point(int(x0 + (b + 1) * w) - 1, y0),
                  cv::Scalar(160, 110, 50), cv::FILLED);
  }
  cv::line(img, {x0, y0}, {x1, y0}, kInk);
  cv::line(img, {x0, y0}, {x0, y1}, kInk);
  for (int i = 0; i <= 4; ++i) {
    const int x = x0 + (x1 - x0) * i / 4;
    text(img, detail::short_number(lo + (hi - lo) * i / 4), {x - 15, y0 + 20}, 0.45);
    const int y = y0 - (y0 - y1) * i / 4;
    text(img, std::to_string(top * i / 4), {x0 - 45, y + 5}, 0.45);
  }
  text(img, title, {x0, 35}, 0.65, 2);
  text(img, xlabel + "  (n = " + std::to_string(values.size()) + ")", {x0 + 180, 465}, 0.5);
  return img;
}

cv::Mat grid(std::span<const cv::Mat> tiles, int columns) {
  if (tiles.empty() || columns < 1) throw Error("a grid needs at least one tile and one column");
  const cv::Mat& first = tiles.front();
  const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
  cv::Mat out(first.rows * rows, first.cols * columns, first.type(), cv::Scalar::all(255));
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    if (tiles[i].size() != first.size() || tiles[i].type() != first.type())
      throw Error("grid tiles differ in size or type");
    const int r = static_cast<int>(i) / columns, c = static_cast<int>(i) % columns;
    tiles[i].copyTo(out(cv::Rect(c * first.cols, r * first.rows, first.cols, first.rows)));
  }
  return out;
}

std::vector<std::uint8_t> encode_png(const cv::Mat& image) { return encode_image(image, ".png"); }

cv::Mat rgb_image(std::span<const Rgb8> rgb, int width, int height) {
  cv::Mat img(height, width, CV_8UC3);
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const Rgb8& c = rgb[static_cast<std::size_t>(v) * width + u];
      img.at<cv::Vec3b>(v, u) = {c.b, c.g, c.r};
    }
  return img;
}

cv::Mat depth_image(std::span<const std::uint16_t> depth, int width, int height) {
  cv::Mat img(height, width, CV_16U);
  std::copy(depth.begin(), depth.end(), img.ptr<std::uint16_t>(0));
  return img;
}

}  // namespace uwgrasp::viz
