// Every seed and every input that once failed a fuzz target (fuzz/corpus, fuzz/regressions) is
// run through the same function as the libFuzzer target, in this build's sanitizers: none may
// escape with anything but a normal return.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <cstring>
#include <iterator>
#include <limits>

#include "fuzz/inputs.hpp"
#include "uwgrasp/camera/files.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace fs = std::filesystem;
using namespace uwgrasp;

namespace {
std::vector<std::uint8_t> bytes_of(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

std::vector<fs::path> inputs_of(const std::string& target, bool past_failures = true) {
  std::vector<fs::path> files;
  for (const char* dir : {"fuzz/corpus/", "fuzz/regressions/"}) {
    if (!past_failures && std::string(dir) == "fuzz/regressions/") continue;
    const fs::path d = fs::path(UWGRASP_SOURCE_DIR) / (dir + target);
    if (!fs::is_directory(d)) continue;
    for (const auto& e : fs::directory_iterator(d))
      if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}
}  // namespace

TEST(FuzzRegressions, EverySeedAndEveryPastFailureReturnsNormally) {
  std::size_t total = 0;
  for (const auto& t : fuzz::targets()) {
    const auto files = inputs_of(t.name);
    EXPECT_FALSE(files.empty()) << "no seed for the fuzz target " << t.name;
    for (const auto& f : files) {
      const auto in = bytes_of(f);
      EXPECT_NO_THROW(t.run(fuzz::Bytes(in.data(), in.size()))) << f;
      ++total;
    }
  }
  EXPECT_GE(total, fuzz::targets().size());
}

TEST(FuzzRegressions, TheSeedsAreValidInputs) {
  // The hand-written seeds are inputs uwgrasp accepts, so the fuzzers start inside the format.
  for (const auto& f : inputs_of("pcd", false)) EXPECT_NO_THROW(io::load_cloud(f.string())) << f;
  for (const auto& f : inputs_of("ply", false)) EXPECT_NO_THROW(io::load_cloud(f.string())) << f;
  for (const auto& f : inputs_of("camera", false)) EXPECT_NO_THROW(camera::read_camera(f.string())) << f;
  for (const auto& f : inputs_of("stereo", false)) EXPECT_NO_THROW(camera::read_stereo(f.string())) << f;
  // What fuzz/ found: each past failure is now refused with an Error naming the file, except
  // the valid_* inputs, valid files that once broke the fuzz target's own check.
  const auto past_failure = [](const fs::path& f) {
    return f.string().find("regressions") != std::string::npos && f.filename().string().rfind("valid_", 0) != 0;
  };
  for (const char* t : {"pcd", "ply"})
    for (const auto& f : inputs_of(t))
      if (past_failure(f)) { EXPECT_THROW(io::load_cloud(f.string()), Error) << f; }
  for (const auto& f : inputs_of("camera"))
    if (past_failure(f)) { EXPECT_THROW(camera::read_camera(f.string()), Error) << f; }
  for (const auto& f : inputs_of("stereo"))
    if (past_failure(f)) { EXPECT_THROW(camera::read_stereo(f.string()), Error) << f; }
}

TEST(FuzzRegressions, RefusalsAreErrorsAndBrokenInvariantsEscape) {
  const std::string cut = "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 9\n"
                          "HEIGHT 1\nPOINTS 9\nDATA binary\n1234";
  const fuzz::Bytes in(reinterpret_cast<const std::uint8_t*>(cut.data()), cut.size());
  EXPECT_NO_THROW(fuzz::pcd(in));  // refused with an Error: a normal return
  EXPECT_THROW(io::load_cloud(fuzz::scratch_file(in, ".pcd")), Error);
  const std::string yaml = "seed: 4\n%%\nthreads=2\n";
  EXPECT_NO_THROW(fuzz::config(fuzz::Bytes(reinterpret_cast<const std::uint8_t*>(yaml.data()), yaml.size())));
}

TEST(FuzzRegressions, ARangeGridCellNamingAMissingVertexIsRefused) {
  // An organised cloud with a hole: PCL writes 11 vertices and a 12-cell range_grid, the last
  // cell "1, index 10". Pointing it past the vertices must be an Error, not garbage points.
  Cloud c;
  for (int i = 0; i < 12; ++i) c.points.emplace_back(0.1f * float(i), 0.0f, 1.0f);
  c.points[5] = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
  c.width = 4, c.height = 3;
  const std::string path = (fs::temp_directory_path() / "uwgrasp_fuzz_grid.ply").string();
  io::save_cloud(path, c);
  EXPECT_EQ(io::load_cloud(path).size(), 12u);
  std::vector<std::uint8_t> b = bytes_of(path);
  ASSERT_GE(b.size(), 5u);
  std::int32_t index = 0;
  std::memcpy(&index, &b[b.size() - 4], 4);
  ASSERT_EQ(index, 10);
  index = 1000;
  std::memcpy(&b[b.size() - 4], &index, 4);
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
  try {
    io::load_cloud(path);
    ADD_FAILURE() << "a range_grid cell naming vertex 1000 of 11 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("range_grid"), std::string::npos) << e.what();
  }
  fs::remove(path);
}
