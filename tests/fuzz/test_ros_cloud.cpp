// The PointCloud2 fuzz input (fuzz/ros_cloud.cpp): its seeds and past failures return normally,
// and a layout that is refused or accepted is told apart by the conversion itself.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/ros_cloud.hpp"

namespace fs = std::filesystem;

namespace {
std::vector<std::uint8_t> message(std::uint16_t w, std::uint16_t h, std::uint16_t step, std::uint32_t row_step,
                                  std::size_t data_bytes) {
  std::vector<std::uint8_t> b;
  auto put = [&](const void* p, std::size_t n) {
    const auto* c = static_cast<const std::uint8_t*>(p);
    b.insert(b.end(), c, c + n);
  };
  const std::uint8_t flags[3] = {0, 0, 3};  // little-endian, not dense, 3 fields
  put(&h, 2), put(&w, 2), put(&step, 2), put(&row_step, 4), put(flags, 3);
  for (std::uint8_t k = 0; k < 3; ++k) {  // x, y, z FLOAT32 at 0, 4, 8
    const std::uint16_t offset = std::uint16_t(4 * k);
    const std::uint8_t type = 7, count = 1;
    put(&k, 1), put(&offset, 2), put(&type, 1), put(&count, 1);
  }
  b.resize(b.size() + data_bytes, 0);
  return b;
}
}  // namespace

TEST(FuzzRosCloud, SeedsAndPastFailuresReturnNormally) {
  std::size_t n = 0;
  for (const char* dir : {"fuzz/regressions/ros_cloud"}) {
    const fs::path d = fs::path(UWGRASP_SOURCE_DIR) / dir;
    if (!fs::is_directory(d)) continue;
    for (const auto& e : fs::directory_iterator(d)) {
      std::ifstream f(e.path(), std::ios::binary);
      const std::vector<std::uint8_t> in{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
      EXPECT_NO_THROW(uwgrasp::fuzz::ros_cloud(in.data(), in.size())) << e.path();
      ++n;
    }
  }
  // Well-formed, short, and absurd layouts: every one returns normally (accepted or refused).
  for (const auto& m : {message(2, 2, 12, 24, 48), message(2, 2, 12, 24, 47), message(65535, 65535, 12, 0, 16),
                        message(1, 1, 0, 0, 0), message(3, 1, 16, 48, 48)}) {
    EXPECT_NO_THROW(uwgrasp::fuzz::ros_cloud(m.data(), m.size()));
    ++n;
  }
  EXPECT_GE(n, 5u);
}
