// The organised path (cloud/organised.hpp) on whole simulated camera frames: it segments a
// noiseless scene as the k-d tree path does, its detections do not depend on the thread count,
// and a stream of frames in one process (segments, or whole detections) gives each frame's one-shot
// result without growing.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "uwgrasp/core/memory.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/grasps_json.hpp"
#include "uwgrasp/segment/objects.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/sim/scene.hpp"

namespace {
using namespace uwgrasp;

// The built-in thesis scene (three objects on the seafloor) seen by the simulator's camera.
sim::Frame thesis_frame(bool noise, std::uint64_t seed, std::uint32_t width = 640, std::uint32_t height = 480) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const sim::World world(scene);
  sim::RenderConfig rc;
  rc.noise.enabled = noise;
  rc.camera.width = width, rc.camera.height = height;
  return sim::render_rgbd(world, sim::camera_pose(scene, {}), rc, seed);
}

io::Config camera_config() {
  io::Config cfg;
  const sim::Scene thesis = sim::builtin_scene("thesis");
  cfg.grasp.frames.camera = *thesis.camera_mount;
  grasp::given_attitude(cfg.grasp.frames, thesis.vehicle.rpy.x(), thesis.vehicle.rpy.y());
  cfg.segment.object.by = segment::ObjectBy::largest;
  return cfg;
}

// Per true object, the best IoU of the scene's whole objects (segment/objects.hpp: its points
// joined where they touch, as the detector selects them) with the object's pixels.
std::map<std::uint16_t, double> best_iou(const sim::Frame& f, const segment::Scene& s) {
  const cloud::Neighbours& nb = s.pre.neighbours;
  const segment::Objects objects =
      segment::connected_objects(s.pre.cloud, nb, segment::connection_gap(nb), 50);
  std::map<std::uint16_t, std::size_t> truth;
  std::map<std::int32_t, std::size_t> size;
  std::map<std::pair<std::uint16_t, std::int32_t>, std::size_t> both;
  for (std::size_t i = 0; i < f.labels.size(); ++i) {
    const std::uint16_t l = f.labels[i];
    const std::int32_t m = s.pre.output_of_input[i];
    const std::int32_t o = m < 0 ? -1 : objects.object_of_point[std::size_t(m)];
    if (l >= sim::kLabelFirstObject) ++truth[l];
    if (o >= 0) ++size[o];
    if (l >= sim::kLabelFirstObject && o >= 0) ++both[{l, o}];
  }
  std::map<std::uint16_t, double> best;
  for (const auto& [l, n] : truth) best[l] = 0.0;
  for (const auto& [key, n] : both)
    best[key.first] = std::max(best[key.first], double(n) / double(truth[key.first] + size[key.second] - n));
  return best;
}

std::size_t resident_kb() {
  long pages = 0, resident = 0;
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
  std::fclose(f);
  return std::size_t(resident) * std::size_t(sysconf(_SC_PAGESIZE)) / 1024;
}

// Runs frame(i) for i < count, stopping at a fatal failure, and checks that the resident set
// does not grow from the 20th frame on. Not in sanitizer builds, which keep freed memory in
// quarantine: there only the frames' own checks count.
void expect_steady(int count, const std::function<void(int)>& frame) {
  [[maybe_unused]] std::size_t rss_early = 0;
  for (int i = 0; i < count && !::testing::Test::HasFatalFailure(); ++i) {
    frame(i);
    if (i == 19) rss_early = resident_kb();
  }
#if !defined(__SANITIZE_ADDRESS__)
  if (::testing::Test::HasFatalFailure()) return;
  const std::size_t rss_late = resident_kb();
  EXPECT_LT(double(rss_late), 1.05 * double(rss_early) + 2048.0)
      << "resident " << rss_early << " kB after 20 frames, " << rss_late << " kB after " << count;
#endif
}
}  // namespace

// On a noiseless frame the organised path finds each object (whole, as the detector selects it)
// as well as the k-d tree path does: the ring and the cross with IoU > 0.8, the barbell in parts
// on both paths (its bar is seen apart from its blocks; the detector gathers them).
TEST(OrganisedFrames, SegmentEveryObjectAsTheKdTreePathDoes) {
  const sim::Frame f = thesis_frame(false, 1);
  io::Config cfg = camera_config();
  const segment::Scene org = segment::segment_scene(f.cloud, cfg.preprocess, cfg.segment, 1);
  cfg.preprocess.organised.enabled = false;
  const segment::Scene kd = segment::segment_scene(f.cloud, cfg.preprocess, cfg.segment, 1);
  ASSERT_TRUE(org.pre.organised);
  ASSERT_FALSE(kd.pre.organised);
  const auto a = best_iou(f, org), b = best_iou(f, kd);
  ASSERT_EQ(a.size(), 3u);
  std::size_t whole = 0;
  for (const auto& [label, iou] : a) {
    EXPECT_GT(iou, b.at(label) - 0.03) << "object " << label << ": k-d tree path " << b.at(label);
    whole += iou > 0.8;
  }
  EXPECT_GE(whole, 2u);
}

// Same seed, same grasps.json, at one thread and two, on a noisy organised frame.
TEST(OrganisedFrames, DetectionIsByteIdenticalAtOneAndTwoThreads) {
  const sim::Frame f = thesis_frame(true, 3);
  const io::Config cfg = camera_config();
  const auto run = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    const grasp::Detection d = grasp::detect(f.cloud, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed);
    EXPECT_TRUE(d.scene.pre.organised);
    EXPECT_FALSE(d.result.grasps.empty());
    nlohmann::json j = io::grasps_to_json(d, cfg, "frame.pcd", "test");
    j.erase("timing_ms");
    return j.dump();
  };
  EXPECT_EQ(run(1), run(2));
}

// A stream of 200 frames (four noisy frames in turn) in one process, as a camera delivers them:
// each frame's segments equal a one-shot call on it, and the process does not grow once the
// first frames' buffers are there to reuse (watched through the resident set; sanitizer builds
// keep freed memory in quarantine, so there only the results are compared).
TEST(OrganisedFrames, AStreamGivesTheOneShotResultsAndDoesNotGrow) {
  keep_freed_memory();
  std::vector<sim::Frame> frames;
  for (std::uint64_t s = 0; s < 4; ++s) frames.push_back(thesis_frame(true, 10 + s, 320, 240));
  const io::Config cfg = camera_config();
  std::vector<std::vector<std::int32_t>> once;
  for (const auto& f : frames)
    once.push_back(segment::input_labels(segment::segment_scene(f.cloud, cfg.preprocess, cfg.segment, 5)));
  expect_steady(200, [&](int i) {
    const std::size_t k = std::size_t(i) % frames.size();
    const segment::Scene s = segment::segment_scene(frames[k].cloud, cfg.preprocess, cfg.segment, 5);
    ASSERT_EQ(segment::input_labels(s), once[k]) << "frame " << i;
  });
}

// The same for whole detections: 200 frames through one Detection and one Workspace
// (grasp::detect's stream form) give each frame's one-shot grasps.json, and the process does not
// grow after the first frames. The grasp engine still allocates a few hundred blocks a frame
// (docs/benchmarks.md); this checks that they come back. Sanitizer builds run 24 frames and
// compare only the results.
TEST(OrganisedFrames, AStreamOfDetectionsGivesTheOneShotResultsAndDoesNotGrow) {
  keep_freed_memory();
#if defined(__SANITIZE_ADDRESS__)
  const int count = 24;
#else
  const int count = 200;
#endif
  std::vector<sim::Frame> frames;
  for (std::uint64_t s = 0; s < 4; ++s) frames.push_back(thesis_frame(true, 30 + s, 320, 240));
  const io::Config cfg = camera_config();
  const auto json_of = [&](const grasp::Detection& d) {
    nlohmann::json j = io::grasps_to_json(d, cfg, "frame.pcd", "test");
    j.erase("timing_ms");
    return j.dump();
  };
  std::vector<std::string> once;
  for (const auto& f : frames) {
    const grasp::Detection d = grasp::detect(f.cloud, cfg.preprocess, cfg.segment, cfg.grasp, 5);
    ASSERT_FALSE(d.result.grasps.empty());  // a comparison of real results
    once.push_back(json_of(d));
  }
  grasp::Detection d;
  segment::Workspace ws;
  expect_steady(count, [&](int i) {
    const std::size_t k = std::size_t(i) % frames.size();
    grasp::detect(frames[k].cloud, cfg.preprocess, cfg.segment, cfg.grasp, 5, d, ws);
    ASSERT_EQ(json_of(d), once[k]) << "frame " << i;
  });
}
