// Line plots: time series of the approach simulation, score curves.
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/viz/picture.hpp"
#include "uwgrasp/viz/plot_text.hpp"

namespace uwgrasp::viz {

namespace {
using detail::kInk;
constexpr int kX0 = 80, kX1 = 560, kY0 = 420, kY1 = 60;  // plot area; the legend is on the right

cv::Scalar series_colour(std::size_t i) {
  static const cv::Scalar palette[] = {{180, 119, 31}, {14, 127, 255}, {44, 160, 44}, {40, 39, 214},
                                       {189, 103, 148}, {75, 86, 140}, {194, 119, 227}, {127, 127, 127}};
  return palette[i % std::size(palette)];
}

struct Range {
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  void add(double v) {
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  void settle() {
    if (lo > hi) lo = 0, hi = 1;
    if (!(hi > lo)) hi = lo + 1;
  }
};
}  // namespace

cv::Mat line_plot(std::span<const Series> series, const Axes& axes) {
  Range xr, yr;
  for (const Series& s : series) {
    if (s.x.size() != s.y.size()) throw Error("line plot '" + s.name + "': x and y differ in length");
    for (double v : s.x) xr.add(v);
    for (double v : s.y) yr.add(v);
  }
  for (double m : axes.y_marks) yr.add(m);
  if (axes.include_zero) yr.add(0.0);
  if (axes.y_lo != axes.y_hi) yr.lo = axes.y_lo, yr.hi = axes.y_hi;
  xr.settle(), yr.settle();
  cv::Mat img(480, 720, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto at = [&](double x, double y) {
    return cv::Point(int(std::lround(kX0 + (x - xr.lo) / (xr.hi - xr.lo) * (kX1 - kX0))),
                     int(std::lround(kY0 - (std::clamp(y, yr.lo, yr.hi) - yr.lo) / (yr.hi - yr.lo) * (kY0 - kY1))));
  };
  for (double m : axes.y_marks)
    for (int x = kX0; x < kX1; x += 12) {
      const cv::Point p = at(xr.lo, m);
      cv::line(img, {x, p.y}, {std::min(x + 6, kX1), p.y}, cv::Scalar(120, 120, 120));
    }
  for (double m : axes.x_marks)
    for (int y = kY1; y < kY0; y += 12) {
      const int x = at(m, yr.lo).x;
      if (x > kX0 && x < kX1) cv::line(img, {x, y}, {x, std::min(y + 6, kY0)}, cv::Scalar(120, 120, 120));
    }
  for (std::size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    for (std::size_t i = 1; i < s.x.size(); ++i)
      if (std::isfinite(s.y[i - 1]) && std::isfinite(s.y[i]) && std::isfinite(s.x[i - 1]) && std::isfinite(s.x[i]))
        cv::line(img, at(s.x[i - 1], s.y[i - 1]), at(s.x[i], s.y[i]), series_colour(k), 2, cv::LINE_AA);
    const int y = kY1 + 10 + 22 * static_cast<int>(k);
    cv::line(img, {kX1 + 15, y - 4}, {kX1 + 40, y - 4}, series_colour(k), 3);
    detail::text(img, s.name, {kX1 + 46, y}, 0.45);
  }
  cv::rectangle(img, {kX0, kY1}, {kX1, kY0}, kInk);
  for (int i = 0; i <= 4; ++i) {
    detail::text(img, detail::short_number(xr.lo + (xr.hi - xr.lo) * i / 4), {kX0 + (kX1 - kX0) * i / 4 - 12, kY0 + 20}, 0.45);
    detail::text(img, detail::short_number(yr.lo + (yr.hi - yr.lo) * i / 4), {8, kY0 - (kY0 - kY1) * i / 4 + 5}, 0.45);
  }
  detail::text(img, axes.title, {kX0, 35}, 0.65, 2);
  detail::text(img, axes.xlabel, {kX0 + (kX1 - kX0) / 2 - 30, 465}, 0.5);
  detail::text(img, axes.ylabel, {8, kY1 - 12}, 0.5);
  return img;
}

}  // namespace uwgrasp::viz
