#include "convert.hpp"

#include <cmath>
#include <cstring>
#include <string>

#include <sensor_msgs/point_cloud2_iterator.h>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp_ros {

using uwgrasp::Error;

namespace {
struct Field {
  std::uint32_t offset = 0;
  std::uint8_t type = 0;
  bool found = false;
};

std::uint32_t type_size(std::uint8_t t) {
  using F = sensor_msgs::PointField;
  switch (t) {
    case F::INT8: case F::UINT8: return 1;
    case F::INT16: case F::UINT16: return 2;
    case F::INT32: case F::UINT32: case F::FLOAT32: return 4;
    case F::FLOAT64: return 8;
    default: return 0;
  }
}

Field find_field(const sensor_msgs::PointCloud2& m, const std::string& name) {
  for (const auto& f : m.fields) {
    if (f.name != name) continue;
    const std::uint32_t size = type_size(f.datatype);
    if (size == 0) throw Error("PointCloud2: field '" + name + "' has unknown datatype " + std::to_string(f.datatype));
    if (std::uint64_t(f.offset) + size * std::uint64_t(std::max<std::uint32_t>(f.count, 1)) > m.point_step)
      throw Error("PointCloud2: field '" + name + "' (offset " + std::to_string(f.offset) +
                  ") runs past point_step " + std::to_string(m.point_step));
    return {f.offset, f.datatype, true};
  }
  return {};
}

float read_coord(const std::uint8_t* p, const Field& f) {
  if (f.type == sensor_msgs::PointField::FLOAT64) {
    double v;
    std::memcpy(&v, p + f.offset, sizeof v);
    return static_cast<float>(v);
  }
  float v;
  std::memcpy(&v, p + f.offset, sizeof v);
  return v;
}

void check_layout(const sensor_msgs::PointCloud2& m) {
  const std::uint64_t n = std::uint64_t(m.width) * m.height;
  if (n == 0) throw Error("PointCloud2: empty (width x height = " + std::to_string(m.width) + " x " + std::to_string(m.height) + ")");
  if (m.is_bigendian) throw Error("PointCloud2: big-endian data is not supported");
  if (m.point_step == 0) throw Error("PointCloud2: point_step is 0");
  if (std::uint64_t(m.row_step) < std::uint64_t(m.width) * m.point_step)
    throw Error("PointCloud2: row_step " + std::to_string(m.row_step) + " < width x point_step (" +
                std::to_string(std::uint64_t(m.width) * m.point_step) + ")");
  if (std::uint64_t(m.data.size()) < std::uint64_t(m.row_step) * m.height)
    throw Error("PointCloud2: data has " + std::to_string(m.data.size()) + " bytes, row_step x height needs " +
                std::to_string(std::uint64_t(m.row_step) * m.height));
}

// Where x, y, z and the colours sit in each point, the message checked first.
struct Layout {
  Field xyz[3];
  Field rgb;
};

Layout layout_of(const sensor_msgs::PointCloud2& m) {
  check_layout(m);
  Layout l;
  const char* names[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    l.xyz[k] = find_field(m, names[k]);
    if (!l.xyz[k].found) throw Error(std::string("PointCloud2: no field '") + names[k] + "'");
    if (l.xyz[k].type != sensor_msgs::PointField::FLOAT32 &&
        l.xyz[k].type != sensor_msgs::PointField::FLOAT64)
      throw Error(std::string("PointCloud2: field '") + names[k] + "' is not FLOAT32 or FLOAT64");
  }
  l.rgb = find_field(m, "rgb");
  if (!l.rgb.found) l.rgb = find_field(m, "rgba");
  if (l.rgb.found && type_size(l.rgb.type) != 4)
    throw Error("PointCloud2: field 'rgb' is not 4 bytes");
  return l;
}

// Into width x height points, row-major: 3 floats each into `xyz`, 3 bytes each into `rgb` when
// the message has colours.
void read_points(const sensor_msgs::PointCloud2& m, const Layout& l, float* xyz,
                 std::uint8_t* rgb) {
  for (std::uint32_t r = 0; r < m.height; ++r) {
    const std::uint8_t* row = m.data.data() + std::size_t(r) * m.row_step;
    for (std::uint32_t col = 0; col < m.width; ++col) {
      const std::uint8_t* p = row + std::size_t(col) * m.point_step;
      const std::size_t i = std::size_t(r) * m.width + col;
      for (int k = 0; k < 3; ++k) xyz[3 * i + k] = read_coord(p, l.xyz[k]);
      if (l.rgb.found) {
        std::uint32_t packed;  // 0x00RRGGBB, as PCL packs it
        std::memcpy(&packed, p + l.rgb.offset, sizeof packed);
        rgb[3 * i] = std::uint8_t(packed >> 16), rgb[3 * i + 1] = std::uint8_t(packed >> 8);
        rgb[3 * i + 2] = std::uint8_t(packed);
      }
    }
  }
}
}  // namespace

PlainCloud from_msg(const sensor_msgs::PointCloud2& m) {
  PlainCloud c;
  from_msg(m, c);
  return c;
}

void from_msg(const sensor_msgs::PointCloud2& m, PlainCloud& c) {
  const Layout l = layout_of(m);
  c.width = m.width;
  c.height = m.height;
  const std::size_t n = std::size_t(m.width) * m.height;
  c.xyz.resize(3 * n);
  c.rgb.resize(l.rgb.found ? 3 * n : 0);
  read_points(m, l, c.xyz.data(), c.rgb.data());
}

void from_msg(const sensor_msgs::PointCloud2& m, Stream& out) {
  const Layout l = layout_of(m);
  const FrameBuffers b = out.frame(m.width, m.height, l.rgb.found);
  read_points(m, l, b.xyz, b.rgb);
}

sensor_msgs::PointCloud2 to_msg(const PlainCloud& c) {
  sensor_msgs::PointCloud2 m;
  sensor_msgs::PointCloud2Modifier mod(m);
  const bool colours = !c.rgb.empty();
  if (colours) mod.setPointCloud2FieldsByString(2, "xyz", "rgb");
  else mod.setPointCloud2FieldsByString(1, "xyz");
  mod.resize(c.size());
  m.width = c.height > 1 ? c.width : static_cast<std::uint32_t>(c.size());
  m.height = c.height > 1 ? c.height : 1;
  m.row_step = m.width * m.point_step;
  m.is_dense = false;
  sensor_msgs::PointCloud2Iterator<float> x(m, "x");
  for (std::size_t i = 0; i < c.size(); ++i, ++x) x[0] = c.xyz[3 * i], x[1] = c.xyz[3 * i + 1], x[2] = c.xyz[3 * i + 2];
  if (colours) {
    sensor_msgs::PointCloud2Iterator<std::uint8_t> b(m, "rgb");  // memory order b, g, r
    for (std::size_t i = 0; i < c.size(); ++i, ++b) b[0] = c.rgb[3 * i + 2], b[1] = c.rgb[3 * i + 1], b[2] = c.rgb[3 * i];
  }
  return m;
}

Pose7 pose7(const geometry_msgs::Transform& t) {
  return {{t.translation.x, t.translation.y, t.translation.z}, {t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w}};
}

geometry_msgs::Transform transform_msg(const Pose7& p) {
  geometry_msgs::Transform t;
  t.translation.x = p.p[0], t.translation.y = p.p[1], t.translation.z = p.p[2];
  t.rotation.x = p.q[0], t.rotation.y = p.q[1], t.rotation.z = p.q[2], t.rotation.w = p.q[3];
  return t;
}

geometry_msgs::Pose pose_msg(const Pose7& p) {
  geometry_msgs::Pose m;
  m.position.x = p.p[0], m.position.y = p.p[1], m.position.z = p.p[2];
  m.orientation.x = p.q[0], m.orientation.y = p.q[1], m.orientation.z = p.q[2], m.orientation.w = p.q[3];
  return m;
}

}  // namespace uwgrasp_ros
