#include "fuzz/inputs.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>  // the IMREAD_ flags only
#include <optional>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/pcd.hpp"
#include "uwgrasp/viz/png_codec.hpp"

namespace uwgrasp::fuzz {

namespace fs = std::filesystem;

namespace {
// The scratch folder lives in memory when /dev/shm exists (a file per execution, millions of
// executions) and is removed when the process ends normally.
struct ScratchDir {
  fs::path dir;
  ScratchDir() {
    std::error_code ec;
    const char* tmp = std::getenv("TMPDIR");
    fs::path base = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm")
                    : tmp                             ? fs::path(tmp)
                                                      : fs::temp_directory_path();
    dir = base / ("uwgrasp-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(dir);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

const fs::path& scratch_dir() {
  static ScratchDir d;
  return d.dir;
}

// A point with any coordinate not finite is no point (is_finite); writers may store it as
// NaN, NaN, NaN (PCL's PLY writer leaves it out of an organised cloud's range_grid).
bool same_point(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  if (!is_finite(a) || !is_finite(b)) return is_finite(a) == is_finite(b);
  return a == b;
}

// A cloud uwgrasp accepted must be one it can write and read back unchanged.
void round_trip(const Cloud& c, const std::string& ext) {
  check_consistent(c, "fuzzed cloud");
  const std::string out = (scratch_dir() / ("round_trip" + ext)).string();
  io::save_cloud(out, c, io::PcdFormat::binary);
  const Cloud back = io::load_cloud(out);
  if (back.size() != c.size() || back.width != c.width || back.height != c.height)
    throw Invariant("round trip changed the cloud's size or layout");
  for (std::size_t i = 0; i < c.size(); ++i)
    if (!same_point(back.points[i], c.points[i])) throw Invariant("round trip changed a point");
  if (back.has_colors() != c.has_colors() || back.has_labels() != c.has_labels())
    throw Invariant("round trip changed the fields");
}

void cloud_file(Bytes in, const std::string& ext) {
  Cloud c;
  try {
    c = io::load_cloud(scratch_file(in, ext));
  } catch (const Error&) {
    return;
  }
  round_trip(c, ext);
}
}  // namespace

std::string scratch_file(Bytes in, const std::string& ext) {
  const fs::path p = scratch_dir() / ("input" + ext);
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(in.data()), static_cast<std::streamsize>(in.size()));
  f.close();
  if (!f) throw std::runtime_error("cannot write the scratch file " + p.string());
  return p.string();
}

// Read with each flag uwgrasp reads images with; an image read must write and read back the same.
void png(Bytes in) {
  const std::string path = scratch_file(in, ".png");
  for (const int flags : {cv::IMREAD_UNCHANGED, cv::IMREAD_ANYDEPTH, cv::IMREAD_GRAYSCALE}) {
    const std::optional<cv::Mat> m = viz::png_detail::decode(path, flags);
    if (!m) continue;
    std::vector<std::uint8_t> bytes;
    if (!viz::png_detail::encode(*m, bytes))
      throw Invariant("an image read from a PNG does not write");
    const std::optional<cv::Mat> back =
        viz::png_detail::decode(scratch_file(bytes, ".back.png"), cv::IMREAD_UNCHANGED);
    if (!back || back->type() != m->type() || back->size() != m->size())
      throw Invariant("an image written back reads with another type or size");
    for (int v = 0; v < m->rows; ++v)
      if (std::memcmp(back->ptr(v), m->ptr(v), m->cols * m->elemSize()) != 0)
        throw Invariant("an image written back reads with other pixels");
  }
}

void pcd(Bytes in) { cloud_file(in, ".pcd"); }
void ply(Bytes in) { cloud_file(in, ".ply"); }

const std::vector<Target>& targets() {
  static const std::vector<Target> all = {
      {"pcd", pcd},       {"ply", ply},       {"config", config},
      {"scene", scene},   {"truth", truth},   {"grasps_json", grasps_json},
      {"camera", camera}, {"stereo", stereo}, {"png", png},
  };
  return all;
}

}  // namespace uwgrasp::fuzz
