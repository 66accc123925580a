// bench/stereo: one 640 x 480 stereo pair -> rectify + match + organised cloud, median over
// repeated pairs in one process, at 1 and 2 threads, for several matcher settings with their
// accuracy on the simulated thesis scene (depth error against the ideal depth image, completeness);
// the real shared pair left01/right01 with the rig calibrated from all 13; and detect from the
// simulated pair to the best grasp, stage by stage.
//   stereo [--repeats N]   (default 20)
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "uwgrasp/camera/calibrate.hpp"
#include "uwgrasp/camera/dense.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/viz/picture.hpp"

using namespace uwgrasp;
namespace fs = std::filesystem;

namespace {
double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

struct Pair {
  std::string name;
  cv::Mat left, right;
  camera::StereoRig rig;
  Cloud truth;  // ideal depth from the left camera (simulated pair only)
};

Pair simulated() {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const sim::World world(scene);
  sim::RenderConfig cfg;
  cfg.water = sim::water_preset("clear");
  const Pose pose = sim::camera_pose(scene, Mount{});
  const sim::StereoFrame s = sim::render_stereo(world, pose, cfg, 1);
  cfg.noise.enabled = false;
  Pair p{"simulated thesis scene",
         viz::rgb_image(s.left, 640, 480),
         viz::rgb_image(s.right, 640, 480),
         {},
         sim::render_rgbd(world, pose, cfg, 1).cloud};
  const auto& k = s.intrinsics;
  p.rig.left = {k.width, k.height, k.fx, k.fy, k.cx, k.cy, {}};
  p.rig.right = p.rig.left;
  p.rig.T = Eigen::Vector3d(-s.baseline, 0, 0);
  return p;
}

// left01/right01 with the rig calibrated from the 13 shared pairs (squares of 25 mm assumed).
std::optional<Pair> real_pair() {
  const fs::path dir = fs::path(UWGRASP_DATA_DIR) / "stereo";
  if (!fs::exists(dir / "left01.jpg")) return std::nullopt;
  std::vector<camera::View> l, r;
  for (const char* n :
       {"01", "02", "03", "04", "05", "06", "07", "08", "09", "11", "12", "13", "14"}) {
    l.push_back(
        {n, cv::imread((dir / (std::string("left") + n + ".jpg")).string(), cv::IMREAD_GRAYSCALE)});
    r.push_back({n, cv::imread((dir / (std::string("right") + n + ".jpg")).string(),
                               cv::IMREAD_GRAYSCALE)});
  }
  const camera::StereoCalibration c = camera::calibrate_stereo(l, r, {9, 6, 0.025});
  return Pair{"real pair left01 (calibrated rig)", l[0].image, r[0].image, c.rig, {}};
}

struct Accuracy {
  double error = 0.0, completeness = 0.0;
};

Accuracy accuracy(const Cloud& got, const Cloud& truth) {
  std::vector<double> rel;
  int near = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const float zt = truth.points[i].z();
    if (!std::isfinite(zt) || zt > 2.0f) continue;
    ++near;
    if (const float z = got.points[i].z(); std::isfinite(z))
      rel.push_back(std::abs(double(z) - zt) / zt);
  }
  return {rel.empty() ? 1.0 : median(rel), double(rel.size()) / std::max(near, 1)};
}

void run(const Pair& p, const std::string& setting, const camera::DenseConfig& cfg, int repeats) {
  const camera::Rectification rect = camera::rectify(p.rig, cfg);
  for (const int threads : {1, 2}) {
    cv::setNumThreads(threads);
    std::map<std::string, std::vector<double>> st;
    std::vector<double> total;
    camera::DenseFrame f;
    for (int r = 0; r < repeats + 1; ++r) {
      StageTimer t;
      f = camera::dense_stereo(p.left, p.right, rect, cfg, p.name, &t);
      if (r == 0) continue;  // the first call warms OpenCV's thread pool
      for (const auto& s : t.stages()) st[s.name].push_back(s.ms);
      total.push_back(t.total_ms());
    }
    const Accuracy a = p.truth.empty() ? Accuracy{NAN, NAN} : accuracy(f.cloud, p.truth);
    std::size_t matched = 0;
    for (const auto& q : f.cloud.points) matched += std::isfinite(q.z());
    std::printf(
        "| %s | %s | %d | %.1f | %.1f | %.1f | **%.1f** | %d | %.2f %% | %.1f %% | %.1f %% |\n",
        p.name.c_str(), setting.c_str(), threads, median(st["rectify"]), median(st["match"]),
        median(st["cloud"]), median(total), rect.num_disparities, 100 * a.error,
        100 * a.completeness, 100.0 * double(matched) / double(f.cloud.size()));
    std::fflush(stdout);
  }
}

void detect_stages(const Pair& p, int repeats) {
  const io::Config cfg;
  const camera::Rectification rect = camera::rectify(p.rig, cfg.stereo);
  cv::setNumThreads(2);
  std::map<std::string, std::vector<double>> st;
  std::vector<std::string> order;
  std::vector<double> total;
  for (int r = 0; r < repeats + 1; ++r) {
    StageTimer t;
    const camera::DenseFrame f =
        camera::dense_stereo(p.left, p.right, rect, cfg.stereo, p.name, &t);
    const grasp::Detection d =
        grasp::detect(f.cloud, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed);
    if (r == 0) continue;
    for (const StageTimer* timer : {static_cast<const StageTimer*>(&t), &d.timer})
      for (const auto& s : timer->stages()) {
        if (!st.count(s.name)) order.push_back(s.name);
        st[s.name].push_back(s.ms);
      }
    total.push_back(t.total_ms() + d.timer.total_ms());
  }
  std::printf("\n%s -> best grasp, default settings, 2 threads, median of %d (ms):\n\n|",
              p.name.c_str(), repeats);
  for (const auto& n : order) std::printf(" %s |", n.c_str());
  std::printf(" total |\n|");
  for (std::size_t i = 0; i <= order.size(); ++i) std::printf("---|");
  std::printf("\n|");
  for (const auto& n : order) std::printf(" %.1f |", median(st[n]));
  std::printf(" **%.1f** |\n", median(total));
}
}  // namespace

int main(int argc, char** argv) {
  int repeats = 20;
  for (int i = 1; i + 1 < argc; ++i)
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::max(1, std::atoi(argv[i + 1]));
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  std::vector<Pair> pairs{simulated()};
  if (auto r = real_pair())
    pairs.push_back(std::move(*r));
  else
    std::fprintf(stderr, "shared data absent: the real pair is skipped\n");
  std::vector<std::pair<std::string, camera::DenseConfig>> settings;
  camera::DenseConfig c;
  settings.emplace_back("default (3way, block 5, 0.5-6 m)", c);
  c.block_size = 3;
  settings.emplace_back("3way, block 3", c);
  c = {}, c.min_range = 0.8;
  settings.emplace_back("3way, 0.8-6 m", c);
  c = {}, c.downscale = 2;
  settings.emplace_back("3way, matched at half size", c);
  c.min_range = 0.8;
  settings.emplace_back("3way, half size, 0.8-6 m", c);
  c = {}, c.mode = "sgbm";
  settings.emplace_back("sgbm (5 paths)", c);
  std::printf(
      "| pair | matcher | threads | rectify ms | match ms | cloud ms | total ms | disparities | "
      "median depth "
      "error <= 2 m | completeness <= 2 m | matched "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& p : pairs)
    for (const auto& [name, cfg] : settings) run(p, name, cfg, repeats);
  detect_stages(pairs.front(), repeats);
  return 0;
}
