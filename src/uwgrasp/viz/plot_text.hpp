#pragma once
// Internal to viz/: the ink and number format the plots share.
#include <opencv2/imgproc.hpp>

#include <cstdio>
#include <string>

namespace uwgrasp::viz::detail {

inline const cv::Scalar kInk(40, 40, 40);

inline void text(cv::Mat& img, const std::string& s, cv::Point at, double scale, int thick = 1) {
  cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, kInk, thick, cv::LINE_AA);
}

// Three significant digits: axis ticks and colour-bar ends.
inline std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace uwgrasp::viz::detail
