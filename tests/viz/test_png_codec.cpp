// viz/png_codec against its oracle, OpenCV's own PNG codec (imgcodecs, linked into this program
// only): every image it writes reads back the same through cv::imdecode, and every PNG it reads
// it reads as cv::imread does, to the byte; what it declines is OpenCV's to read.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>
#include <vector>

#include "uwgrasp/viz/png_codec.hpp"
#ifdef UWGRASP_COUNT_MALLOC
#include "alloc_count.hpp"
#endif

namespace {
namespace png = uwgrasp::viz::png_detail;

std::filesystem::path temp(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("uwgrasp_png_" + std::to_string(::getpid()) + "_" + name);
}

void write(const std::filesystem::path& p, const std::vector<std::uint8_t>& bytes) {
  std::ofstream f(p, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// A PNG of one IHDR, one IDAT and IEND, each with its CRC, whatever the header claims.
std::vector<std::uint8_t> handmade_png(std::uint32_t width, std::uint32_t height,
                                       const std::vector<std::uint8_t>& raw) {
  std::vector<std::uint8_t> out{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  const auto be32 = [](std::vector<std::uint8_t>& v, std::uint32_t x) {
    for (int s = 24; s >= 0; s -= 8) v.push_back(std::uint8_t(x >> s));
  };
  const auto chunk = [&](const char* type, const std::vector<std::uint8_t>& data) {
    be32(out, std::uint32_t(data.size()));
    std::vector<std::uint8_t> body;
    for (int k = 0; k < 4; ++k) body.push_back(std::uint8_t(type[k]));
    for (const std::uint8_t b : data) body.push_back(b);
    out.insert(out.end(), body.begin(), body.end());
    be32(out, std::uint32_t(crc32(0, body.data(), uInt(body.size()))));
  };
  std::vector<std::uint8_t> ihdr;
  be32(ihdr, width), be32(ihdr, height);
  ihdr.insert(ihdr.end(),
              {8, 0, 0, 0, 0});  // 8-bit grey, deflate, no filter method, not interlaced
  std::vector<std::uint8_t> packed(compressBound(uLong(raw.size())));
  uLongf size = uLongf(packed.size());
  compress(packed.data(), &size, raw.data(), uLong(raw.size()));
  packed.resize(size);
  chunk("IHDR", ihdr), chunk("IDAT", packed), chunk("IEND", {});
  return out;
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  if (a.type() != b.type() || a.size() != b.size()) return false;
  for (int v = 0; v < a.rows; ++v)
    if (std::memcmp(a.ptr(v), b.ptr(v), a.cols * a.elemSize()) != 0) return false;
  return true;
}

// Random images of every type the encoder takes, odd sizes, noise and flat runs (the run-length
// strategy's case) both, one a view into a larger image (rows not contiguous).
std::vector<cv::Mat> images() {
  std::vector<cv::Mat> out;
  cv::RNG rng(7);
  for (const int depth : {CV_8U, CV_16U})
    for (const int channels : {1, 3, 4})
      for (const cv::Size size : {cv::Size(1, 1), cv::Size(37, 53), cv::Size(640, 3)}) {
        cv::Mat m(size, CV_MAKETYPE(depth, channels));
        rng.fill(m, cv::RNG::UNIFORM, 0, depth == CV_8U ? 256 : 65536);
        if (size.width > 30)
          m.rowRange(0, size.height / 2).setTo(cv::Scalar::all(depth == CV_8U ? 200 : 40000));
        out.push_back(m);
      }
  cv::Mat big(60, 80, CV_8UC3);
  rng.fill(big, cv::RNG::UNIFORM, 0, 256);
  out.push_back(big(cv::Rect(5, 7, 41, 29)));
  return out;
}

TEST(PngCodec, WritesWhatOpenCvReadsBackExactly) {
  for (const cv::Mat& m : images()) {
    std::vector<std::uint8_t> bytes;
    ASSERT_TRUE(png::encode(m, bytes)) << cv::typeToString(m.type());
    const cv::Mat back = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
    EXPECT_TRUE(same(back, m)) << cv::typeToString(m.type()) << " " << m.cols << " x " << m.rows;
  }
}

// The same settings as imencode's, so the same file, byte for byte.
TEST(PngCodec, WritesTheBytesImencodeWrites) {
  for (const cv::Mat& m : images()) {
    std::vector<std::uint8_t> ours, theirs;
    ASSERT_TRUE(png::encode(m, ours));
    ASSERT_TRUE(cv::imencode(".png", m, theirs));
    EXPECT_EQ(ours, theirs) << cv::typeToString(m.type()) << " " << m.cols << " x " << m.rows;
  }
}

TEST(PngCodec, DeclinesWhatItDoesNotWrite) {
  std::vector<std::uint8_t> bytes{1, 2, 3};
  EXPECT_FALSE(png::encode(cv::Mat(), bytes));
  EXPECT_TRUE(bytes.empty());
  EXPECT_FALSE(png::encode(cv::Mat(4, 4, CV_32FC1, cv::Scalar(1.0)), bytes));
  EXPECT_FALSE(png::encode(cv::Mat(4, 4, CV_8UC2, cv::Scalar::all(1)), bytes));
  const int dims[3] = {2, 2, 2};
  EXPECT_FALSE(png::encode(cv::Mat(3, dims, CV_8UC1, cv::Scalar(0)), bytes));
}

// Every image written by OpenCV and read with the flags uwgrasp reads with: where png_codec
// reads it, it reads what imread reads; it reads every plain kind it says it does.
TEST(PngCodec, ReadsAsImreadDoes) {
  const int all_flags[] = {cv::IMREAD_UNCHANGED, cv::IMREAD_ANYDEPTH, cv::IMREAD_GRAYSCALE,
                           cv::IMREAD_COLOR};
  int read = 0, declined = 0;
  for (const cv::Mat& m : images()) {
    const auto path = temp("oracle.png");
    ASSERT_TRUE(cv::imwrite(path.string(), m));
    for (const int flags : all_flags) {
      const std::optional<cv::Mat> ours = png::decode(path.string(), flags);
      const bool grey = m.channels() == 1,
                 plain = grey ? flags != cv::IMREAD_COLOR &&
                                    (flags != cv::IMREAD_GRAYSCALE || m.depth() == CV_8U)
                              : flags == cv::IMREAD_UNCHANGED;
      EXPECT_EQ(ours.has_value(), plain) << cv::typeToString(m.type()) << " flags " << flags;
      if (!ours) {
        ++declined;
        continue;
      }
      ++read;
      EXPECT_TRUE(same(*ours, cv::imread(path.string(), flags)))
          << cv::typeToString(m.type()) << " flags " << flags;
    }
    std::filesystem::remove(path);
  }
  EXPECT_GT(read, 20);
  EXPECT_GT(declined, 20);
}

// The fuzz target's hand-written seeds (fuzz/corpus/png, written by hand, not by libpng): the
// plain ones read as imread reads them (an interlaced one among them), the others are left to it.
TEST(PngCodec, ReadsTheFuzzSeedsAsImreadDoes) {
  const std::filesystem::path dir =
      std::filesystem::path(UWGRASP_SOURCE_DIR) / "fuzz" / "corpus" / "png";
  int plain = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string path = e.path().string(), name = e.path().filename().string();
    const bool is_plain = name.rfind("plain_", 0) == 0;
    plain += is_plain;
    EXPECT_EQ(png::decode(path, cv::IMREAD_UNCHANGED).has_value(), is_plain) << name;
    for (const int flags : {cv::IMREAD_UNCHANGED, cv::IMREAD_ANYDEPTH, cv::IMREAD_GRAYSCALE})
      if (const std::optional<cv::Mat> ours = png::decode(path, flags)) {
        EXPECT_TRUE(same(*ours, cv::imread(path, flags))) << name << " flags " << flags;
      }
  }
  EXPECT_GE(plain, 6);
}

// Kinds left to OpenCV: one bit a pixel, not a PNG at all, a PNG cut short, a missing file.
TEST(PngCodec, LeavesOtherFilesToOpenCv) {
  const auto bilevel = temp("bilevel.png"), jpeg = temp("image.jpg"), cut = temp("cut.png");
  cv::Mat bits(16, 16, CV_8UC1);
  cv::randu(bits, 0, 2);
  bits *= 255;
  ASSERT_TRUE(cv::imwrite(bilevel.string(), bits, {cv::IMWRITE_PNG_BILEVEL, 1}));
  EXPECT_FALSE(png::decode(bilevel.string(), cv::IMREAD_UNCHANGED).has_value());
  ASSERT_TRUE(cv::imwrite(jpeg.string(), cv::Mat(16, 16, CV_8UC3, cv::Scalar(1, 2, 3))));
  EXPECT_FALSE(png::decode(jpeg.string(), cv::IMREAD_UNCHANGED).has_value());
  cv::Mat noise(64, 64, CV_8UC3);
  cv::randu(noise, 0, 256);
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(png::encode(noise, bytes));
  for (const std::size_t keep :
       {std::size_t(8), std::size_t(40), bytes.size() / 2, bytes.size() - 13}) {
    write(cut, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + std::ptrdiff_t(keep)));
    EXPECT_FALSE(png::decode(cut.string(), cv::IMREAD_UNCHANGED).has_value()) << keep << " bytes";
  }
  EXPECT_FALSE(png::decode(temp("missing.png").string(), cv::IMREAD_UNCHANGED).has_value());
  // A well-formed header over far too little data (30000 x 30000, within OpenCV's 2^30 pixels):
  // declined without the 900 MB of its frame (a header of a frame the file does hold is read,
  // the same builder's oracle).
  write(cut, handmade_png(30000, 30000, std::vector<std::uint8_t>(4 * 30001, 0)));
#ifdef UWGRASP_COUNT_MALLOC
  const auto asked = uwgrasp::alloc_count::count(
      [&] { EXPECT_FALSE(png::decode(cut.string(), cv::IMREAD_UNCHANGED).has_value()); });
  EXPECT_LT(asked.bytes, std::size_t(1) << 20);
#else
  EXPECT_FALSE(png::decode(cut.string(), cv::IMREAD_UNCHANGED).has_value());
#endif
  // Three rows, each its filter byte (none) and three pixels.
  const std::vector<std::uint8_t> raw{0, 0, 9, 200, 0, 1, 9, 200, 0, 2, 9, 200};
  write(cut, handmade_png(3, 3, raw));
  const std::optional<cv::Mat> small = png::decode(cut.string(), cv::IMREAD_UNCHANGED);
  ASSERT_TRUE(small.has_value());
  EXPECT_TRUE(same(*small, cv::imread(cut.string(), cv::IMREAD_UNCHANGED)));
  std::filesystem::remove(bilevel), std::filesystem::remove(jpeg), std::filesystem::remove(cut);
}

}  // namespace
