// uwgrasp_fuzz_seeds OUT_DIR [DATA_DIR]: writes the generated part of each target's seed corpus
// to OUT_DIR/<target>/ (clouds in every PCD and PLY encoding uwgrasp writes, the default config,
// camera and rig calibrations, PointCloud2 layouts) and copies the small real clouds of DATA_DIR
// (../shared/data). The hand-written seeds are in fuzz/corpus/.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>

#include "uwgrasp/camera/files.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/pcd.hpp"

namespace fs = std::filesystem;
using namespace uwgrasp;

namespace {
Cloud small_cloud(bool organised, bool colours, bool labels) {
  Cloud c;
  for (int i = 0; i < 12; ++i) {
    const float v = 0.1f * float(i);
    c.points.emplace_back(v, -v, 1.0f + v);
    if (colours) c.colors.push_back({std::uint8_t(20 * i), 100, std::uint8_t(255 - 20 * i)});
    if (labels) c.labels.push_back(std::uint32_t(i % 3));
  }
  if (organised) {
    c.points[5] = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
    c.width = 4, c.height = 3;
  } else {
    c.width = 12;
  }
  return c;
}

void clouds(const fs::path& out) {
  fs::create_directories(out / "pcd");
  fs::create_directories(out / "ply");
  int n = 0;
  for (bool organised : {false, true})
    for (bool colours : {false, true}) {
      const Cloud c = small_cloud(organised, colours, colours && organised);
      io::save_cloud((out / "ply" / ("gen" + std::to_string(n) + ".ply")).string(), c);
      io::save_cloud((out / "pcd" / ("ascii" + std::to_string(n) + ".pcd")).string(), c, io::PcdFormat::ascii);
      io::save_cloud((out / "pcd" / ("binary" + std::to_string(n) + ".pcd")).string(), c, io::PcdFormat::binary);
      io::save_cloud((out / "pcd" / ("compressed" + std::to_string(n) + ".pcd")).string(), c,
                     io::PcdFormat::binary_compressed);
      ++n;
    }
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

void calibrations(const fs::path& out) {
  camera::Pinhole c;
  c.width = 640, c.height = 480, c.fx = 525, c.fy = 525, c.cx = 319.5, c.cy = 239.5;
  c.distortion = {-0.1, 0.01, 0.001, -0.001, 0.0};
  write(out / "camera" / "ros.yaml", camera::camera_yaml(c, "left"));
  camera::StereoRig s;
  s.left = s.right = c;
  s.T = Eigen::Vector3d(-0.12, 0, 0);
  write(out / "stereo" / "rig.yaml", camera::stereo_yaml(s));
}

// PointCloud2 seeds in fuzz/ros_cloud.cpp's layout: 2 x 2 points of x, y, z (FLOAT32) and rgb.
void ros_clouds(const fs::path& out) {
  std::string b;
  auto put = [&](auto v) { b.append(reinterpret_cast<const char*>(&v), sizeof v); };
  put(std::uint16_t(2)), put(std::uint16_t(2)), put(std::uint16_t(16)), put(std::uint32_t(32));
  put(std::uint8_t(0)), put(std::uint8_t(0)), put(std::uint8_t(4));
  const std::uint8_t names[4] = {0, 1, 2, 3};  // x, y, z, rgb in ros_cloud.cpp's name table
  for (std::uint8_t k = 0; k < 4; ++k)
    put(names[k]), put(std::uint16_t(4 * k)), put(std::uint8_t(7)), put(std::uint8_t(1));
  for (int i = 0; i < 4; ++i) put(0.1f * float(i)), put(0.2f), put(1.5f), put(std::uint32_t(0x00ff8040));
  write(out / "ros_cloud" / "xyzrgb_2x2.bin", b);
}

void shared_clouds(const fs::path& out, const fs::path& data) {
  // The small real clouds; the 640 x 480 ones are far beyond the fuzzers' input size.
  for (const char* name : {"bun0.pcd", "sac_plane_test.pcd"}) {
    const fs::path f = data / "clouds" / name;
    std::error_code ec;
    if (fs::is_regular_file(f, ec)) fs::copy_file(f, out / "pcd" / name, fs::copy_options::overwrite_existing);
  }
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: uwgrasp_fuzz_seeds OUT_DIR [DATA_DIR]\n";
    return 2;
  }
  try {
    const fs::path out = argv[1];
    clouds(out);
    write(out / "config" / "default.yaml", io::to_yaml(io::Config{}));
    write(out / "config" / "with_sets.yaml", "seed: 3\npreprocess:\n  outliers: {k: 8}\n%%\nseed=4\npreprocess.outliers.k=12\n");
    calibrations(out);
    ros_clouds(out);
    if (argc > 2) shared_clouds(out, argv[2]);
  } catch (const std::exception& e) {
    std::cerr << "uwgrasp_fuzz_seeds: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
