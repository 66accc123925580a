#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "shapes.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace uwgrasp::io {

namespace {
namespace fs = std::filesystem;

fs::path tmp_dir() {
  const fs::path d = fs::temp_directory_path() / ("uwgrasp_io_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

Cloud full_cloud() {
  Cloud c;
  c.width = 3, c.height = 2;
  for (int i = 0; i < 6; ++i) {
    c.points.emplace_back(0.1f * i, -0.2f * i, 1.0f + i);
    c.normals.emplace_back(0.f, 0.6f, -0.8f);
    c.curvature.push_back(0.01f * i);
    c.colors.push_back({std::uint8_t(40 * i), std::uint8_t(255 - i), 7});
    c.labels.push_back(std::uint32_t(20 + i));
  }
  c.points[4] = Eigen::Vector3f::Constant(std::nanf(""));
  c.viewpoint = {0.5f, -1.f, 2.f};
  return c;
}

void expect_equal(const Cloud& a, const Cloud& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (is_finite(a.points[i])) {
      EXPECT_EQ(a.points[i], b.points[i]);
    } else {
      EXPECT_FALSE(is_finite(b.points[i]));
    }
  }
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.curvature, b.curvature);
  EXPECT_EQ(a.colors, b.colors);
  EXPECT_EQ(a.labels, b.labels);
  EXPECT_EQ(a.viewpoint, b.viewpoint);
}

void write_file(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }
}  // namespace

TEST(Pcd, RoundTripsEveryFieldInEveryFormat) {
  const Cloud c = full_cloud();
  const fs::path d = tmp_dir();
  for (auto [name, fmt] : {std::pair{"a.pcd", PcdFormat::ascii}, {"b.pcd", PcdFormat::binary},
                           {"c.pcd", PcdFormat::binary_compressed}}) {
    save_cloud((d / name).string(), c, fmt);
    expect_equal(c, load_cloud((d / name).string()));
  }
  Cloud dense = full_cloud();
  dense.points[4] = {1, 1, 1};
  save_cloud((d / "d.ply").string(), dense);
  const Cloud ply = load_cloud((d / "d.ply").string());
  ASSERT_EQ(ply.size(), dense.size());
  EXPECT_EQ(ply.points, dense.points);
  EXPECT_EQ(ply.colors, dense.colors);
  fs::remove_all(d);
}

// PCL reads lines after DATA as header lines while they look like one (io/header_check.cpp):
// binary data beginning '#' or VERSION is read right, data beginning with a header key is not, so
// the writer falls back to another encoding and every cloud written reads back bit for bit.
TEST(Pcd, EveryCloudWrittenReadsBackWhateverItsDataBeginsWith) {
  const fs::path d = tmp_dir();
  Rng r(3);
  Cloud c;
  const auto u = [&](float lo, float hi) { return lo + (hi - lo) * float(r.uniform()); };
  for (int i = 0; i < 500; ++i) c.points.emplace_back(u(-5, 5), u(-5, 5), u(0, 9));
  make_unorganised(c);
  const auto data_line = [](const fs::path& p) {
    std::ifstream f(p);
    for (std::string line; std::getline(f, line);)
      if (line.rfind("DATA ", 0) == 0) return line;
    return std::string();
  };
  struct Case { std::string start, data; };
  for (const Case& k : {Case{"#ab", "DATA binary"}, Case{"VERSION", "DATA binary"},
                        Case{"SIZE", "DATA binary_compressed"}, Case{"#a\nWIDTH 9\n", "DATA binary_compressed"},
                        Case{"\n\nFIELDS x", "DATA binary_compressed"}}) {
    std::memcpy(c.points[0].data(), k.start.data(), std::min<std::size_t>(12, k.start.size()));
    if (!is_finite(c.points[0])) c.points[0].z() = 1.0f;
    const fs::path p = d / "first.pcd";
    save_cloud(p.string(), c, PcdFormat::binary);
    EXPECT_EQ(data_line(p), k.data) << k.start;
    expect_equal(c, load_cloud(p.string()));
  }
  save_cloud((d / "a.pcd").string(), c, PcdFormat::ascii);
  expect_equal(c, load_cloud((d / "a.pcd").string()));
  fs::remove_all(d);
}

TEST(Pcd, LoadsTheSharedRealClouds) {
  UWGRASP_DATA_OR_SKIP(mug, "clouds/table_scene_mug_stereo_textured.pcd");
  UWGRASP_DATA_OR_SKIP(bun, "clouds/bun0.pcd");
  UWGRASP_DATA_OR_SKIP(mosd, "clouds/mOSD_learn0.pcd");
  UWGRASP_DATA_OR_SKIP(milk, "clouds/milk_color.pcd");
  const Cloud m = load_cloud(mug);  // binary_compressed, organised, NaNs
  EXPECT_EQ(m.width, 640u);
  EXPECT_EQ(m.height, 480u);
  EXPECT_TRUE(m.has_colors());
  std::size_t nan = 0;
  for (const auto& p : m.points) nan += !is_finite(p);
  EXPECT_GT(nan, 0u);
  const Cloud b = load_cloud(bun);  // ascii with normals and curvature
  EXPECT_EQ(b.size(), 397u);
  EXPECT_TRUE(b.has_normals());
  EXPECT_TRUE(b.has_curvature());
  const Cloud o = load_cloud(mosd);  // labels
  ASSERT_TRUE(o.has_labels());
  EXPECT_GE(*std::max_element(o.labels.begin(), o.labels.end()), 20u);
  EXPECT_EQ(load_cloud(milk).size(), 13704u);  // rgba
  EXPECT_TRUE(load_cloud(milk).has_colors());
}

TEST(Pcd, BadFilesAreErrorsNamingTheFile) {
  const fs::path d = tmp_dir();
  auto expect_error = [&](const fs::path& p, const std::string& word) {
    try {
      load_cloud(p.string());
      FAIL() << p;
    } catch (const Error& e) {
      const std::string w = e.what();
      EXPECT_NE(w.find(p.string()), std::string::npos) << w;
      EXPECT_NE(w.find(word), std::string::npos) << w;
      EXPECT_EQ(w.find('\n'), std::string::npos) << "one line: " << w;
    }
  };
  expect_error(d / "missing.pcd", "no such file");
  write_file(d / "empty.pcd", "");
  expect_error(d / "empty.pcd", "empty");
  write_file(d / "garbage.pcd", "this is not a point cloud\n");
  expect_error(d / "garbage.pcd", "malformed");
  write_file(d / "noxyz.pcd",
             "VERSION .7\nFIELDS a b\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nWIDTH 1\nHEIGHT 1\n"
             "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n1 2\n");
  expect_error(d / "noxyz.pcd", "x, y and z");
  write_file(d / "x.txt", "1 2 3\n");
  expect_error(d / "x.txt", "extension");
  // Binary files cut in half (PCL pads files to whole pages, so cut well into the data).
  Cloud c;
  Rng r(1);
  for (int i = 0; i < 20000; ++i) c.points.emplace_back(r.uniform(), r.uniform(), r.uniform());
  make_unorganised(c);
  for (auto [name, fmt] : {std::pair{"cut.pcd", PcdFormat::binary}, {"cut_c.pcd", PcdFormat::binary_compressed}}) {
    save_cloud((d / name).string(), c, fmt);
    fs::resize_file(d / name, fs::file_size(d / name) / 2);
    expect_error(d / name, "truncated");
  }
  fs::remove_all(d);
}

TEST(Pcd, FailedSaveLeavesNoFile) {
  const fs::path d = tmp_dir();
  EXPECT_THROW(save_cloud((d / "x.xyz").string(), full_cloud()), Error);
  EXPECT_THROW(save_cloud((d / "nodir" / "x.pcd").string(), full_cloud()), Error);
  Cloud bad = full_cloud();
  bad.labels.pop_back();
  EXPECT_THROW(save_cloud((d / "bad.pcd").string(), bad), Error);
  EXPECT_TRUE(fs::is_empty(d));
  fs::remove_all(d);
}

}  // namespace uwgrasp::io
