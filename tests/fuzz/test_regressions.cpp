// Every seed and every input that once failed a fuzz target (fuzz/corpus, fuzz/regressions) is
// run through the same function as the libFuzzer target, in this build's sanitizers: none may
// escape with anything but a normal return.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

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
  // What fuzz/ found: each past failure is now refused with an Error naming the file.
  for (const char* t : {"pcd", "ply"}) {
    for (const auto& f : inputs_of(t)) {
      if (f.string().find("regressions") != std::string::npos) {
        EXPECT_THROW(io::load_cloud(f.string()), Error) << f;
      }
    }
  }
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
