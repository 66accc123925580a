#pragma once
// Headless pictures (PNG): a cloud seen from a chosen viewpoint, with wireframes (grasps drawn
// as grippers) coloured by a value, a colour bar and a legend.
#include <opencv2/core.hpp>

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::viz {

// A virtual camera orbiting `target`: azimuth/elevation turn the view away from the input
// cloud's own viewing direction (camera optical frame: looking along +z, y down).
struct View {
  int width = 1280, height = 960;
  double azimuth = 0.35;    // rad, about the cloud's vertical (-y)
  double elevation = 0.25;  // rad, upwards
  double distance = 0.0;    // m from target; 0: fit the drawn points
  double hfov = 0.8;        // rad
};

struct Wire {
  std::vector<std::array<Eigen::Vector3f, 2>> segments;  // in the cloud's frame
  double value = 0.0;                                    // colour by this (drawn best last)
  int thickness = 2;
  std::optional<Rgb8> colour;  // a fixed colour (a category) instead of the value's
};

struct Picture {
  std::string title;
  std::string value_name = "score";  // the colour bar's label
  std::vector<std::string> legend;   // lines of text under the title
  bool colour_by_label = false;      // points coloured by label (segments) instead of RGB
  double point_size = 0.0;           // pixels; 0: from the point density
  // Categories of fixed-colour wires, shown as a key in place of the colour bar.
  std::vector<std::pair<std::string, Rgb8>> key;
};

// Draws `cloud` (finite points) and `wires`. The view's target is the centroid of `focus` when
// it is not empty, else of the whole cloud. Returns an 8-bit BGR image.
cv::Mat draw(const Cloud& cloud, std::span<const Wire> wires, const Picture& pic,
             const View& view = {}, std::span<const Eigen::Vector3f> focus = {});

// A histogram of `values` in `bins` bins over [lo, hi] (lo == hi: the data's range).
cv::Mat histogram(std::span<const double> values, int bins, double lo, double hi,
                  const std::string& title, const std::string& xlabel);

// Lines of y over x in one 720 x 480 plot, each in its own colour with its name in the legend.
struct Series {
  std::string name;
  std::vector<double> x, y;  // same length; non-finite points break the line
};
struct Axes {
  std::string title, xlabel, ylabel;
  double y_lo = 0, y_hi = 0;     // y range; equal: the data's range
  std::vector<double> y_marks;   // dashed horizontal lines (limits, tolerances)
  std::vector<double> x_marks;   // dashed vertical lines (events)
  bool include_zero = true;      // the automatic y range reaches 0
};
// Throws Error when a series' x and y differ in length.
cv::Mat line_plot(std::span<const Series> series, const Axes& axes);

// Tiles of one size and type laid out row by row, `columns` per row, blank (white) where the
// last row is short. Throws Error when the tiles differ in size or type.
cv::Mat grid(std::span<const cv::Mat> tiles, int columns);

// Encodes PNG bytes; Throws Error if OpenCV cannot.
std::vector<std::uint8_t> encode_png(const cv::Mat& image);
// Images from the simulator's buffers: RGB8 -> BGR, and 16-bit depth as is.
cv::Mat rgb_image(std::span<const Rgb8> rgb, int width, int height);
cv::Mat depth_image(std::span<const std::uint16_t> depth, int width, int height);

// Colour of a value in [0, 1] on the colour bar (viridis), and a distinct colour per label.
cv::Vec3b value_colour(double t);
cv::Vec3b label_colour(std::uint32_t label);

}  // namespace uwgrasp::viz
