#pragma once
// The ROS PointCloud2 conversion as a fuzz input (C++17: it includes ROS message headers).
#include <cstddef>
#include <cstdint>

namespace uwgrasp::fuzz {

// The first bytes give the message's header fields (height, width, point_step, row_step,
// endianness, up to 8 fields with name, offset, datatype and count), the rest is its data.
void ros_cloud(const std::uint8_t* data, std::size_t size);

}  // namespace uwgrasp::fuzz
