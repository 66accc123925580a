// viz/ image files through the codecs module loaded on first use: lossless round trips, errors
// that name the file, and a program that does not link OpenCV's codecs at all.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>  // IMREAD_ flags only
#include <string>
#include <vector>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/viz/image_files.hpp"
#include "uwgrasp/viz/picture.hpp"

namespace {

std::filesystem::path temp(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("uwgrasp_image_" + std::to_string(::getpid()) + "_" + name);
}

void write(const std::filesystem::path& p, const std::vector<std::uint8_t>& bytes) {
  std::ofstream f(p, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// PNG keeps 8-bit colour and 16-bit depth to the bit, read back with the flags the CLI uses.
TEST(ImageFiles, PngRoundTripsAreLossless) {
  cv::Mat colour(37, 53, CV_8UC3), depth(37, 53, CV_16UC1);
  cv::randu(colour, 0, 256);
  cv::randu(depth, 0, 65536);
  const auto a = temp("colour.png"), b = temp("depth.png");
  write(a, uwgrasp::viz::encode_png(colour));
  write(b, uwgrasp::viz::encode_image(depth, ".png"));
  const cv::Mat c = uwgrasp::viz::read_image(a.string(), cv::IMREAD_UNCHANGED);
  const cv::Mat d = uwgrasp::viz::read_image(b.string(), cv::IMREAD_ANYDEPTH);
  const cv::Mat grey = uwgrasp::viz::read_image(a.string(), cv::IMREAD_GRAYSCALE);
  std::filesystem::remove(a), std::filesystem::remove(b);
  EXPECT_EQ(grey.type(), CV_8UC1);
  EXPECT_EQ(grey.size(), colour.size());
  ASSERT_EQ(c.type(), CV_8UC3);
  ASSERT_EQ(d.type(), CV_16UC1);
  EXPECT_EQ(cv::norm(c, colour, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(d, depth, cv::NORM_INF), 0.0);
}

TEST(ImageFiles, BadFilesAreNamed) {
  const auto missing = temp("missing.png");
  try {
    uwgrasp::viz::read_image(missing.string(), cv::IMREAD_UNCHANGED);
    FAIL() << "no error";
  } catch (const uwgrasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string() + ": no such file"), std::string::npos) << e.what();
  }
  const auto text = temp("text.png");
  write(text, {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'});
  try {
    uwgrasp::viz::read_image(text.string(), cv::IMREAD_UNCHANGED);
    FAIL() << "no error";
  } catch (const uwgrasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find(text.string() + ": cannot read the image"), std::string::npos) << e.what();
  }
  std::filesystem::remove(text);
  EXPECT_THROW(uwgrasp::viz::encode_png(cv::Mat()), uwgrasp::Error);
  EXPECT_THROW(uwgrasp::viz::encode_image(cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(0)), ".no-such-format"),
               uwgrasp::Error);
}

std::string mapped_libraries() {
  std::ifstream maps("/proc/self/maps");
  std::string line, all;
  while (std::getline(maps, line)) all += line + "\n";
  return all;
}

// The point of the module: this test program reads and writes images without OpenCV's codecs
// (and their hundred-odd libraries) among the libraries it was started with, and PNGs (the
// pictures, the simulator's frames, depth and stereo images) without loading them at all.
TEST(ImageFiles, CodecsAreNotLinkedIntoThePrograms) {
  ASSERT_TRUE(std::ifstream("/proc/self/maps").good());
  // ctest runs each test in a process of its own; run together, an earlier test may have loaded it.
  const bool loaded_before = mapped_libraries().find("libopencv_imgcodecs") != std::string::npos;
  cv::Mat colour(8, 8, CV_8UC3, cv::Scalar::all(7)), depth(8, 8, CV_16UC1, cv::Scalar(1234));
  const auto a = temp("plain.png"), b = temp("plain_depth.png");
  write(a, uwgrasp::viz::encode_png(colour));
  write(b, uwgrasp::viz::encode_image(depth, ".png"));
  EXPECT_EQ(
      cv::norm(uwgrasp::viz::read_image(a.string(), cv::IMREAD_UNCHANGED), colour, cv::NORM_INF),
      0.0);
  EXPECT_EQ(
      cv::norm(uwgrasp::viz::read_image(b.string(), cv::IMREAD_ANYDEPTH), depth, cv::NORM_INF),
      0.0);
  std::filesystem::remove(a), std::filesystem::remove(b);
  if (!loaded_before) {
    EXPECT_EQ(mapped_libraries().find("libopencv_imgcodecs"), std::string::npos);
  }
  (void)uwgrasp::viz::encode_image(colour, ".jpg");  // loads the module
  const std::string all = mapped_libraries();
  EXPECT_NE(all.find("libuwgrasp_imagecodecs.so"), std::string::npos);
  EXPECT_NE(all.find("libopencv_imgcodecs"), std::string::npos);  // through the module
  // and not through the program's own dependencies:
  const std::string exe = std::filesystem::read_symlink("/proc/self/exe").string();
  FILE* p = ::popen(("readelf -d '" + exe + "' 2>/dev/null").c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string dynamic;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p) != nullptr) dynamic += buf;
  ::pclose(p);
  if (dynamic.empty()) GTEST_SKIP() << "readelf not available";
  EXPECT_EQ(dynamic.find("libopencv_imgcodecs"), std::string::npos);
}

}  // namespace
