#include "uwgrasp/io/pcl_blob.hpp"

#include <pcl/PCLPointField.h>

#include <cmath>
#include <cstring>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::io {

namespace {
using Field = pcl::PCLPointField;

const Field* find_field(const pcl::PCLPointCloud2& b, const char* name) {
  for (const auto& f : b.fields)
    if (f.name == name) return &f;
  return nullptr;
}

std::size_t type_size(std::uint8_t t) {
  switch (t) {
    case Field::INT8: case Field::UINT8: return 1;
    case Field::INT16: case Field::UINT16: return 2;
    case Field::INT32: case Field::UINT32: case Field::FLOAT32: return 4;
    case Field::FLOAT64: return 8;
    default: return 0;
  }
}

template <class T>
T load(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

double read_number(const std::uint8_t* p, std::uint8_t t) {
  switch (t) {
    case Field::INT8: return load<std::int8_t>(p);
    case Field::UINT8: return load<std::uint8_t>(p);
    case Field::INT16: return load<std::int16_t>(p);
    case Field::UINT16: return load<std::uint16_t>(p);
    case Field::INT32: return load<std::int32_t>(p);
    case Field::UINT32: return load<std::uint32_t>(p);
    case Field::FLOAT32: return load<float>(p);
    case Field::FLOAT64: return load<double>(p);
    default: return std::nan("");
  }
}

// Reads field `f` of point i as a double; `f` was validated against point_step.
struct Reader {
  const pcl::PCLPointCloud2& b;
  double operator()(const Field& f, std::size_t i) const {
    return read_number(&b.data[i * b.point_step + f.offset], f.datatype);
  }
  std::uint32_t packed(const Field& f, std::size_t i) const {
    return load<std::uint32_t>(&b.data[i * b.point_step + f.offset]);
  }
};

void validate(const pcl::PCLPointCloud2& b, const std::string& src) {
  for (const auto& f : b.fields) {
    const std::size_t sz = type_size(f.datatype);
    if (sz == 0) throw Error(src + ": field '" + f.name + "' has an unknown data type");
    if (f.offset + sz > b.point_step)
      throw Error(src + ": field '" + f.name + "' lies outside the point record");
  }
  const std::size_t n = static_cast<std::size_t>(b.width) * b.height;
  if (b.data.size() < n * b.point_step)
    throw Error(src + ": data holds " + std::to_string(b.data.size()) + " bytes, " +
                std::to_string(n) + " points need " + std::to_string(n * b.point_step));
}

void read_colors(const pcl::PCLPointCloud2& b, const Reader& rd, Cloud& c) {
  const std::size_t n = c.points.size();
  const Field* packed = find_field(b, "rgb");
  if (!packed) packed = find_field(b, "rgba");
  if (packed && type_size(packed->datatype) == 4) {
    c.colors.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t v = rd.packed(*packed, i);
      c.colors[i] = {std::uint8_t(v >> 16), std::uint8_t(v >> 8), std::uint8_t(v)};
    }
    return;
  }
  const Field *r = find_field(b, "red"), *g = find_field(b, "green"), *bl = find_field(b, "blue");
  if (r && g && bl) {
    c.colors.resize(n);
    auto ch = [&](const Field& f, std::size_t i) {
      return static_cast<std::uint8_t>(std::clamp(rd(f, i), 0.0, 255.0));
    };
    for (std::size_t i = 0; i < n; ++i) c.colors[i] = {ch(*r, i), ch(*g, i), ch(*bl, i)};
  }
}
}  // namespace

Cloud from_blob(const pcl::PCLPointCloud2& b, const std::string& src) {
  validate(b, src);
  const Field *x = find_field(b, "x"), *y = find_field(b, "y"), *z = find_field(b, "z");
  if (!x || !y || !z) throw Error(src + ": the cloud has no x, y and z fields");
  const Reader rd{b};
  Cloud c;
  const std::size_t n = static_cast<std::size_t>(b.width) * b.height;
  c.width = b.width;
  c.height = b.height;
  c.points.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    c.points[i] = Eigen::Vector3d(rd(*x, i), rd(*y, i), rd(*z, i)).cast<float>();
  read_colors(b, rd, c);
  const Field *nx = find_field(b, "normal_x"), *ny = find_field(b, "normal_y"),
              *nz = find_field(b, "normal_z");
  if (nx && ny && nz) {
    c.normals.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      c.normals[i] = Eigen::Vector3d(rd(*nx, i), rd(*ny, i), rd(*nz, i)).cast<float>();
  }
  if (const Field* cv = find_field(b, "curvature")) {
    c.curvature.resize(n);
    for (std::size_t i = 0; i < n; ++i) c.curvature[i] = static_cast<float>(rd(*cv, i));
  }
  if (const Field* l = find_field(b, "label")) {
    c.labels.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double v = rd(*l, i);
      c.labels[i] = std::isfinite(v) && v >= 0 ? static_cast<std::uint32_t>(v) : 0u;
    }
  }
  if (c.height == 0) c.height = 1;
  return c;
}

pcl::PCLPointCloud2 to_blob(const Cloud& c) {
  pcl::PCLPointCloud2 b;
  auto add = [&](const char* name, std::uint8_t type) {
    Field f;
    f.name = name;
    f.offset = b.point_step;
    f.datatype = type;
    f.count = 1;
    b.fields.push_back(f);
    b.point_step += static_cast<std::uint32_t>(type_size(type));
  };
  add("x", Field::FLOAT32), add("y", Field::FLOAT32), add("z", Field::FLOAT32);
  if (c.has_colors()) add("rgb", Field::FLOAT32);  // PCL's packed-float convention
  if (c.has_normals()) add("normal_x", Field::FLOAT32), add("normal_y", Field::FLOAT32),
      add("normal_z", Field::FLOAT32);
  if (c.has_curvature()) add("curvature", Field::FLOAT32);
  if (c.has_labels()) add("label", Field::UINT32);
  b.width = c.width;
  b.height = c.height;
  b.is_dense = true;
  for (const auto& p : c.points) b.is_dense = b.is_dense && is_finite(p);
  b.row_step = b.point_step * b.width;
  b.data.resize(c.size() * b.point_step);
  for (std::size_t i = 0; i < c.size(); ++i) {
    std::uint8_t* p = &b.data[i * b.point_step];
    std::memcpy(p, c.points[i].data(), 12);
    std::size_t off = 12;
    if (c.has_colors()) {
      const std::uint32_t v = (std::uint32_t(c.colors[i].r) << 16) |
                              (std::uint32_t(c.colors[i].g) << 8) | c.colors[i].b;
      std::memcpy(p + off, &v, 4), off += 4;
    }
    if (c.has_normals()) std::memcpy(p + off, c.normals[i].data(), 12), off += 12;
    if (c.has_curvature()) std::memcpy(p + off, &c.curvature[i], 4), off += 4;
    if (c.has_labels()) std::memcpy(p + off, &c.labels[i], 4);
  }
  return b;
}

}  // namespace uwgrasp::io
