// The libFuzzer target of the ROS PointCloud2 conversion (C++17, like the rest of the ROS side).
#include <cstddef>
#include <cstdint>

#include "fuzz/ros_cloud.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  uwgrasp::fuzz::ros_cloud(data, size);
  return 0;
}
