#include "fuzz/ros_cloud.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "convert.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::fuzz {

namespace {
// Reads little-endian integers off the front of the input; zeros once it runs out.
struct Reader {
  const std::uint8_t* p;
  std::size_t left;
  template <typename T>
  T take() {
    T v = 0;
    const std::size_t n = left < sizeof(T) ? left : sizeof(T);
    std::memcpy(&v, p, n);
    p += n, left -= n;
    return v;
  }
};

// Names a real driver might send, and some it should not.
const char* const kNames[] = {"x", "y", "z", "rgb", "rgba", "intensity", "label", "", "X", "normal_x"};

sensor_msgs::PointCloud2 message(Reader& r) {
  sensor_msgs::PointCloud2 m;
  m.height = r.take<std::uint16_t>();
  m.width = r.take<std::uint16_t>();
  m.point_step = r.take<std::uint16_t>();
  m.row_step = r.take<std::uint32_t>();
  m.is_bigendian = r.take<std::uint8_t>() == 1;
  m.is_dense = r.take<std::uint8_t>() & 1;
  const int fields = r.take<std::uint8_t>() % 9;
  for (int i = 0; i < fields; ++i) {
    sensor_msgs::PointField f;
    f.name = kNames[r.take<std::uint8_t>() % (sizeof kNames / sizeof kNames[0])];
    f.offset = r.take<std::uint16_t>();
    f.datatype = r.take<std::uint8_t>();
    f.count = r.take<std::uint8_t>();
    m.fields.push_back(f);
  }
  m.data.assign(r.p, r.p + r.left);
  return m;
}

bool same(float a, float b) { return a == b || (std::isnan(a) && std::isnan(b)); }
}  // namespace

void ros_cloud(const std::uint8_t* data, std::size_t size) {
  Reader r{data, size};
  const sensor_msgs::PointCloud2 m = message(r);
  // The node's path reads straight into a stream's frame (reused over inputs, as the node's is):
  // it accepts what the PlainCloud path accepts, and writes only within the frame it sized.
  static uwgrasp_ros::Stream stream;
  bool into_stream = true;
  try {
    uwgrasp_ros::from_msg(m, stream);
  } catch (const uwgrasp::Error&) {
    into_stream = false;
  }
  uwgrasp_ros::PlainCloud c;
  try {
    c = uwgrasp_ros::from_msg(m);
  } catch (const uwgrasp::Error&) {
    if (into_stream)
      throw std::logic_error("the stream read a message the PlainCloud read refuses");
    return;
  }
  if (!into_stream)
    throw std::logic_error("the stream refused a message the PlainCloud read accepts");
  if (c.size() != std::size_t(m.width) * m.height) throw std::logic_error("point count is not width x height");
  // What the node accepted, converted back to a message and read again, is the same cloud.
  const uwgrasp_ros::PlainCloud back = uwgrasp_ros::from_msg(uwgrasp_ros::to_msg(c));
  if (back.size() != c.size() || back.rgb.size() != c.rgb.size())
    throw std::logic_error("PointCloud2 round trip changed the cloud's size or fields");
  for (std::size_t i = 0; i < c.xyz.size(); ++i)
    if (!same(back.xyz[i], c.xyz[i])) throw std::logic_error("PointCloud2 round trip changed a point");
}

}  // namespace uwgrasp::fuzz
