#include "uwgrasp/viz/picture.hpp"
#include "uwgrasp/viz/plot_text.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace uwgrasp::viz {

namespace {
const cv::Scalar kBackground(38, 28, 18);  // BGR: deep-water navy
const cv::Scalar kText(235, 235, 235);

struct Camera {
  Eigen::Matrix3f R;  // columns: view x (right), y (down), z (forward) in the cloud frame
  Eigen::Vector3f eye;
  float f, cx, cy;
  // Pixel and depth; depth <= 0 when behind the camera.
  Eigen::Vector3f project(const Eigen::Vector3f& p) const {
    const Eigen::Vector3f q = R.transpose() * (p - eye);
    if (q.z() <= 1e-4f) return {0, 0, -1};
    return {f * q.x() / q.z() + cx, f * q.y() / q.z() + cy, q.z()};
  }
};

Eigen::Vector3f mean_of(std::span<const Eigen::Vector3f> pts) {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (const auto& p : pts)
    if (p.allFinite()) s += p.cast<double>(), ++n;
  return n ? (s / double(n)).cast<float>() : Eigen::Vector3f(0, 0, 1);
}

// Radius around the target holding 95 % of the points (a few far outliers do not shrink the view).
float extent(std::span<const Eigen::Vector3f> pts, const Eigen::Vector3f& c) {
  std::vector<float> d;
  for (const auto& p : pts)
    if (p.allFinite()) d.push_back((p - c).norm());
  if (d.empty()) return 0.5f;
  const auto k = d.begin() + static_cast<std::ptrdiff_t>(0.95 * double(d.size() - 1));
  std::nth_element(d.begin(), k, d.end());
  return std::max(*k, 0.02f);
}

Camera make_camera(const View& v, const Eigen::Vector3f& target, float radius) {
  const Eigen::Vector3f up(0, -1, 0);
  const Eigen::Vector3f f = (Eigen::AngleAxisf(float(v.azimuth), up) *
                             Eigen::AngleAxisf(float(-v.elevation), Eigen::Vector3f::UnitX()) *
                             Eigen::Vector3f::UnitZ()).normalized();
  const float half = 0.5f * float(v.hfov);
  const float dist = v.distance > 0 ? float(v.distance) : 1.6f * radius / std::tan(half);
  Camera c;
  const Eigen::Vector3f x = f.cross(up).normalized();
  c.R.col(0) = x, c.R.col(1) = f.cross(x), c.R.col(2) = f;
  c.eye = target - dist * f;
  c.f = 0.5f * float(v.width) / std::tan(half);
  c.cx = 0.5f * float(v.width), c.cy = 0.5f * float(v.height);
  return c;
}

void draw_points(cv::Mat& img, const Cloud& cloud, const Camera& cam, const Picture& pic) {
  cv::Mat zbuf(img.rows, img.cols, CV_32F, cv::Scalar(std::numeric_limits<float>::max()));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    if (!p.allFinite()) continue;
    const Eigen::Vector3f q = cam.project(p);
    if (q.z() <= 0) continue;
    const int s = pic.point_size > 0 ? int(pic.point_size)
                                     : std::clamp(int(std::lround(cam.f * 0.0025f / q.z())), 1, 6);
    cv::Vec3b c(200, 200, 200);
    if (pic.colour_by_label && cloud.has_labels()) c = label_colour(cloud.labels[i]);
    else if (cloud.has_colors()) c = cv::Vec3b(cloud.colors[i].b, cloud.colors[i].g, cloud.colors[i].r);
    const int u0 = int(q.x()) - s / 2, v0 = int(q.y()) - s / 2;
    for (int v = std::max(v0, 0); v < std::min(v0 + s, img.rows); ++v)
      for (int u = std::max(u0, 0); u < std::min(u0 + s, img.cols); ++u)
        if (q.z() < zbuf.at<float>(v, u)) zbuf.at<float>(v, u) = q.z(), img.at<cv::Vec3b>(v, u) = c;
  }
}

// Darkens the picture under r towards the background, so that light text drawn there stays
// legible over bright points and wires (a near view of a grasp fills the frame with both).
void shade(cv::Mat& img, cv::Rect r) {
  r &= cv::Rect(0, 0, img.cols, img.rows);
  if (r.empty()) return;
  cv::Mat roi = img(r);
  cv::addWeighted(roi, 0.25, cv::Mat(roi.size(), roi.type(), kBackground), 0.75, 0.0, roi);
}

int text_width(const std::string& s, double scale, int thickness) {
  int baseline = 0;
  return cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &baseline).width;
}

void draw_colour_bar(cv::Mat& img, double lo, double hi, const std::string& name) {
  const int x = img.cols - 70, top = img.rows / 5, h = img.rows * 3 / 5;
  shade(img, cv::Rect(x - 26, top - 50, img.cols - (x - 26), h + 76));  // the labels' reach
  for (int i = 0; i < h; ++i) {
    const cv::Vec3b c = value_colour(1.0 - double(i) / (h - 1));
    cv::line(img, {x, top + i}, {x + 18, top + i}, cv::Scalar(c[0], c[1], c[2]));
  }
  cv::rectangle(img, {x, top}, {x + 18, top + h}, kText);
  const auto label = [&](double v, int y) {
    cv::putText(img, detail::short_number(v), {x - 6, y}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kText, 1, cv::LINE_AA);
  };
  label(hi, top - 8);
  label(lo, top + h + 18);
  cv::putText(img, name, {x - 20, top - 30}, cv::FONT_HERSHEY_SIMPLEX, 0.5, kText, 1, cv::LINE_AA);
}

void draw_wires(cv::Mat& img, std::span<const Wire> wires, const Camera& cam, const Picture& pic) {
  if (wires.empty()) return;
  double lo = wires[0].value, hi = lo;
  for (const auto& w : wires) lo = std::min(lo, w.value), hi = std::max(hi, w.value);
  std::vector<std::size_t> order(wires.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  // Best last, so it is drawn on top.
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return wires[a].value < wires[b].value; });
  bool valued = false;
  for (const auto i : order) {
    const double t = hi > lo ? (wires[i].value - lo) / (hi - lo) : 1.0;
    const std::optional<Rgb8>& fixed = wires[i].colour;
    valued |= !fixed;
    const cv::Vec3b c = fixed ? cv::Vec3b(fixed->b, fixed->g, fixed->r) : value_colour(t);
    for (const auto& s : wires[i].segments) {
      const Eigen::Vector3f a = cam.project(s[0]), b = cam.project(s[1]);
      if (a.z() <= 0 || b.z() <= 0) continue;
      cv::line(img, cv::Point2f(a.x(), a.y()), cv::Point2f(b.x(), b.y()), cv::Scalar(c[0], c[1], c[2]),
               wires[i].thickness, cv::LINE_AA);
    }
  }
  if (valued) draw_colour_bar(img, lo, hi, pic.value_name);
}

void draw_key(cv::Mat& img, const Picture& pic) {
  int y = img.rows / 5;
  if (!pic.key.empty())
    shade(img, cv::Rect(img.cols - 216, y - 20, 216, 24 * int(pic.key.size()) + 8));
  for (const auto& [name, c] : pic.key) {
    const int x = img.cols - 210;
    cv::rectangle(img, {x, y - 12}, {x + 24, y + 2}, cv::Scalar(c.b, c.g, c.r), cv::FILLED);
    cv::putText(img, name, {x + 32, y}, cv::FONT_HERSHEY_SIMPLEX, 0.5, kText, 1, cv::LINE_AA);
    y += 24;
  }
}

// The title and the legend's lines, top left, on a shaded panel as wide as the longest.
void draw_header(cv::Mat& img, const Picture& pic) {
  int width = pic.title.empty() ? 0 : text_width(pic.title, 0.75, 2);
  for (const auto& line : pic.legend) width = std::max(width, text_width(line, 0.5, 1));
  if (width == 0) return;
  const int height = (pic.title.empty() ? 0 : 28) + 22 * int(pic.legend.size());
  shade(img, cv::Rect(4, 4, width + 20, height + 12));
  int y = 28;
  if (!pic.title.empty()) {
    cv::putText(img, pic.title, {14, y}, cv::FONT_HERSHEY_SIMPLEX, 0.75, kText, 2, cv::LINE_AA);
    y += 28;
  }
  for (const auto& line : pic.legend) {
    cv::putText(img, line, {14, y}, cv::FONT_HERSHEY_SIMPLEX, 0.5, kText, 1, cv::LINE_AA);
    y += 22;
  }
}
}  // namespace

cv::Mat draw(const Cloud& cloud, std::span<const Wire> wires, const Picture& pic, const View& view,
             std::span<const Eigen::Vector3f> focus) {
  cv::Mat img(view.height, view.width, CV_8UC3, kBackground);
  const std::span<const Eigen::Vector3f> around = focus.empty() ? std::span(cloud.points) : focus;
  const Eigen::Vector3f target = mean_of(around);
  const Camera cam = make_camera(view, target, extent(around, target));
  draw_points(img, cloud, cam, pic);
  draw_wires(img, wires, cam, pic);
  draw_key(img, pic);
  draw_header(img, pic);
  return img;
}

}  // namespace uwgrasp::viz
