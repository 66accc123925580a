#include "uwgrasp/segment/select.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::segment {

namespace {
struct Named {
  const char* name;
  std::array<bool, 3> channels;
};
constexpr std::array<Named, 6> kColors{{{"red", {true, false, false}},
                                        {"green", {false, true, false}},
                                        {"blue", {false, false, true}},
                                        {"yellow", {true, true, false}},
                                        {"cyan", {false, true, true}},
                                        {"magenta", {true, false, true}}}};

const Named& named(const std::string& color) {
  for (const auto& n : kColors)
    if (color == n.name) return n;
  throw Error("unknown colour '" + color + "' (use red, green, blue, yellow, cyan or magenta)");
}
}  // namespace

float color_intensity(Rgb8 c, const std::string& color) {
  const Named& n = named(color);
  const float v[3] = {c.r / 255.0f, c.g / 255.0f, c.b / 255.0f};
  float weakest_in = 1.0f, strongest_out = 0.0f;
  for (int i = 0; i < 3; ++i)
    n.channels[i] ? weakest_in = std::min(weakest_in, v[i]) : strongest_out = std::max(strongest_out, v[i]);
  return std::max(0.0f, weakest_in - strongest_out);
}

std::vector<SegmentInfo> describe_segments(const Cloud& cloud, const Segmentation& seg,
                                           const std::string& color) {
  std::vector<SegmentInfo> info;
  describe_segments(cloud, seg, color, info);
  return info;
}

void describe_segments(const Cloud& cloud, const Segmentation& seg, const std::string& color,
                       std::vector<SegmentInfo>& info) {
  named(color);  // validate the name even for colourless clouds
  info.assign(seg.segments.size(), SegmentInfo{});
  for (std::size_t s = 0; s < seg.segments.size(); ++s) {
    const auto& idx = seg.segments[s];
    SegmentInfo& si = info[s];
    si.points = idx.size();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), rgb = Eigen::Vector3d::Zero();
    double inten = 0.0;
    for (auto i : idx) {
      sum += cloud.points[i].cast<double>();
      if (cloud.has_colors()) {
        const Rgb8 c = cloud.colors[i];
        rgb += Eigen::Vector3d(c.r, c.g, c.b);
        inten += color_intensity(c, color);
      }
    }
    const double n = std::max<std::size_t>(1, idx.size());
    si.centroid = (sum / n).cast<float>();
    rgb /= n;
    si.mean_color = {static_cast<std::uint8_t>(std::lround(rgb.x())),
                     static_cast<std::uint8_t>(std::lround(rgb.y())),
                     static_cast<std::uint8_t>(std::lround(rgb.z()))};
    si.intensity = static_cast<float>(inten / n);
    si.distance = (si.centroid - cloud.viewpoint).norm();
    si.extent = extent_of(cloud, idx);
  }
}

float extent_of(const Cloud& cloud, std::span<const std::uint32_t> idx) {
  Eigen::AlignedBox3f box;
  for (const auto i : idx) box.extend(cloud.points[i]);
  return idx.empty() ? 0.0f : box.diagonal().norm();
}

void throw_only_fragments(std::size_t count, const std::string& what, const ObjectConfig& cfg) {
  char value[32];
  std::snprintf(value, sizeof value, "%g", double(cfg.min_extent));
  throw Error("no object: none of " + std::to_string(count) + " " + what +
              " is wider than segment.object.min_extent " + value + " m (marine snow, noise)");
}

bool geometric(const ObjectConfig& cfg) {
  return cfg.by == ObjectBy::nearest || cfg.by == ObjectBy::largest || cfg.by == ObjectBy::point;
}

bool fragment(float extent, const ObjectConfig& cfg) {
  return geometric(cfg) && cfg.min_extent > 0.0f && extent <= cfg.min_extent;
}

std::size_t select_object(const std::vector<SegmentInfo>& info, const ObjectConfig& cfg) {
  if (info.empty()) throw Error("no segments: nothing to select as the object of interest");
  const auto wide = [&](const SegmentInfo& s) { return !fragment(s.extent, cfg); };
  const std::size_t first =
      std::size_t(std::find_if(info.begin(), info.end(), wide) - info.begin());
  if (first == info.size()) throw_only_fragments(info.size(), "segments", cfg);
  auto best = [&](auto better) {
    std::size_t b = first;
    for (std::size_t s = first + 1; s < info.size(); ++s)
      if (wide(info[s]) && better(info[s], info[b])) b = s;
    return b;
  };
  switch (cfg.by) {
    case ObjectBy::label:
      if (cfg.label >= info.size())
        throw Error("object label:" + std::to_string(cfg.label) + " does not exist (" +
                    std::to_string(info.size()) + " segments)");
      return cfg.label;
    case ObjectBy::nearest:
      return best([](const auto& a, const auto& b) { return a.distance < b.distance; });
    case ObjectBy::largest:
      return best([](const auto& a, const auto& b) { return a.points > b.points; });
    case ObjectBy::point: {
      const Eigen::Vector3f p = cfg.point.cast<float>();
      return best([&](const auto& a, const auto& b) {
        return (a.centroid - p).squaredNorm() < (b.centroid - p).squaredNorm();
      });
    }
    case ObjectBy::color: {
      const std::size_t b =
          best([](const auto& a, const auto& c) { return a.intensity > c.intensity; });
      if (info[b].intensity < cfg.min_intensity)
        throw Error("no " + cfg.color + " segment: the most " + cfg.color + " of " +
                    std::to_string(info.size()) + " segments has intensity " +
                    std::to_string(info[b].intensity) + " < segment.object.min_intensity " +
                    std::to_string(cfg.min_intensity));
      return b;
    }
  }
  throw Error("unknown object selection mode");
}

std::vector<std::size_t> object_segments(const std::vector<SegmentInfo>& info, std::size_t selected,
                                         const ObjectConfig& cfg) {
  std::vector<std::size_t> out{selected};
  if (cfg.merge_radius <= 0.0f) return out;
  const float r2 = cfg.merge_radius * cfg.merge_radius;
  for (std::size_t s = 0; s < info.size(); ++s)
    if (s != selected && info[s].intensity >= cfg.min_intensity &&
        (info[s].centroid - info[selected].centroid).squaredNorm() <= r2)
      out.push_back(s);
  return out;
}

}  // namespace uwgrasp::segment
