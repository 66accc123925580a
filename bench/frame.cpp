// bench/frame: raw 640x480 frame -> segments and -> best grasp, median over repeated frames in
// one process (as a camera stream would run), at 1 and 2 threads; the k-d tree path on the same
// frames; and PCL's organised chain (IntegralImageNormalEstimation +
// OrganizedMultiPlaneSegmentation + OrganizedConnectedComponentSegmentation) on the same frames.
//   frame [--repeats N] [--frame NAME] [--alone [--threads T]] [--config FILE] [--set K=V ...]
//   (default 20 repeats; NAME: a frame below or "simulated"; --config and --set as the CLI's, on
//   top of `segment.object.by=largest`). --alone: each frame's segments,
//   then its detections, as streams of their own at 1 and 2 threads (or T only), nothing else in
//   between (as a node that only segments, or only detects, runs them); no other table.
// Also counts the heap allocations of one more frame of the warm stream (alloc_count.hpp). The
// segments stream reuses one Scene and one Workspace (segment/pipeline.hpp), as a node would.
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "alloc_count.hpp"
#include "pcl_organised.hpp"
#include "scene.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/memory.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/pcd.hpp"

using namespace uwgrasp;

namespace {
double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double time_ms(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

struct Row {
  double segments = 0, grasp = 0, kd_segments = 0;
  std::map<std::string, std::vector<double>> stages;
  alloc_count::Allocations seg_alloc, grasp_alloc;  // one more frame of the warm stream
};

Row run_uwgrasp(const Cloud& frame, io::Config cfg, int repeats) {
  Row row;
  std::vector<double> seg, grasp, kd;
  segment::Scene stream;  // a stream's: one Scene and one Workspace, frame after frame
  segment::Workspace ws;
  const auto segments = [&] {
    segment::segment_scene(frame, cfg.preprocess, cfg.segment, cfg.seed, stream, ws);
  };
  grasp::Detection d;  // and a stream's detection, as a node keeps it
  segment::Workspace detect_ws;
  const auto detection = [&] {
    grasp::detect(frame, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed, d, detect_ws);
  };
  for (int r = 0; r < repeats; ++r) {
    seg.push_back(time_ms(segments));
    grasp.push_back(time_ms(detection));
    for (const auto& st : d.timer.stages()) row.stages[st.name].push_back(st.ms);
  }
  row.seg_alloc = alloc_count::count(segments);
  row.grasp_alloc = alloc_count::count(detection);
  cfg.preprocess.organised.enabled = false;
  for (int r = 0; r < std::max(3, repeats / 4); ++r)
    kd.push_back(time_ms([&] { segment::segment_scene(frame, cfg.preprocess, cfg.segment, cfg.seed); }));
  row.segments = median(seg), row.grasp = median(grasp), row.kd_segments = median(kd);
  return row;
}

// Streams of one kind of call alone: what runs in between changes glibc's heap (a large free
// raises its thresholds), so the default tables' interleaved timings are not a lone stream's.
void run_alone(const std::vector<std::pair<std::string, Cloud>>& frames, const io::Config& cfg,
               int repeats, const std::vector<int>& thread_counts) {
  std::printf(
      "| frame | threads | segments ms (segments alone) | best grasp ms (detections alone) | "
      "best grasp ms (one-shot detections alone) |\n"
      "|---|---|---|---|---|\n");
  for (const auto& [name, frame] : frames)
    for (const int threads : thread_counts) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                      std::size_t(threads));
      std::vector<double> seg, grasp, once;
      segment::Scene stream;  // a stream's, as above
      segment::Workspace ws;
      grasp::Detection d;
      try {
        for (int r = 0; r < repeats; ++r)
          seg.push_back(time_ms([&] {
            segment::segment_scene(frame, cfg.preprocess, cfg.segment, cfg.seed, stream, ws);
          }));
        for (int r = 0; r < repeats; ++r)
          grasp.push_back(time_ms([&] {
            grasp::detect(frame, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed, d, ws);
          }));
        for (int r = 0; r < repeats; ++r)
          once.push_back(time_ms(
              [&] { grasp::detect(frame, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed); }));
      } catch (const Error& e) {
        std::printf("| %s | %d | %s | | |\n", name.c_str(), threads, e.what());
        continue;
      }
      std::printf("| %s | %d | %.1f | %.1f | %.1f |\n", name.c_str(), threads, median(seg),
                  median(grasp), median(once));
      std::fflush(stdout);
    }
}
}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();  // a stream of frames: the first frame's buffers serve the rest
  int repeats = 20;
  std::string only;  // one frame's name, or every frame
  bool alone = false;
  std::vector<int> thread_counts = {1, 2};
  std::string config;
  std::vector<std::string> sets = {"segment.object.by=largest"};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--alone"))
      alone = true;
    else if (i + 1 < argc && !std::strcmp(argv[i], "--repeats"))
      repeats = std::max(1, std::atoi(argv[++i]));
    else if (i + 1 < argc && !std::strcmp(argv[i], "--frame"))
      only = argv[++i];
    else if (i + 1 < argc && !std::strcmp(argv[i], "--threads"))
      thread_counts = {std::max(1, std::atoi(argv[++i]))};
    else if (i + 1 < argc && !std::strcmp(argv[i], "--config"))
      config = argv[++i];
    else if (i + 1 < argc && !std::strcmp(argv[i], "--set"))
      sets.emplace_back(argv[++i]);
    else {
      std::fprintf(stderr, "frame: unknown or incomplete argument '%s'\n", argv[i]);
      return 2;
    }
  }
  io::Config cfg;
  try {
    cfg = io::load_config(config, sets);
  } catch (const Error& e) {
    std::fprintf(stderr, "frame: %s\n", e.what());
    return 2;
  }
  std::vector<std::pair<std::string, Cloud>> frames;
  const std::string dir = std::string(UWGRASP_DATA_DIR) + "/clouds/";
  for (const char* f : {"table_scene_mug_stereo_textured", "mOSD_learn0", "mOSD_learn17",
                        "mOSD_learn25", "mOSD_learn33"})
    if ((only.empty() || only == f) && std::filesystem::exists(dir + f + ".pcd"))
      frames.emplace_back(f, io::load_cloud(dir + f + ".pcd"));
  if (only.empty() || only == "simulated") frames.emplace_back("simulated thesis scene", bench::seafloor_scene(640, 480));
  if (alone) {
    run_alone(frames, cfg, repeats, thread_counts);
    return 0;
  }
  std::printf("| frame | threads | segments ms | best grasp ms | k-d tree path segments ms | "
              "PCL organised chain ms | PCL / uwgrasp (segments) |\n|---|---|---|---|---|---|---|\n");
  std::vector<std::pair<std::string, Row>> stage_rows;
  for (const auto& [name, frame] : frames) {
    const auto pcl_cloud = bench::to_pcl_organised(frame);
    std::vector<double> pcl_ms;
    for (int r = 0; r < repeats; ++r) pcl_ms.push_back(time_ms([&] { bench::pcl_organised_chain(pcl_cloud); }));
    const double pcl = median(pcl_ms);
    for (const int threads : {1, 2}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
      Row row;
      try {
        row = run_uwgrasp(frame, cfg, repeats);
      } catch (const Error& e) {
        std::printf("| %s | %d | %s | | | %.1f | |\n", name.c_str(), threads, e.what(), pcl);
        continue;
      }
      std::printf("| %s | %d | %.1f | %.1f | %.1f | %.1f | %.1fx |\n", name.c_str(), threads,
                  row.segments, row.grasp, row.kd_segments, pcl, pcl / row.segments);
      std::fflush(stdout);
      if (threads == 2) stage_rows.emplace_back(name, row);
    }
  }
  std::printf("\nMedian stage times (ms) of the whole detection at 2 threads:\n\n| frame |");
  const std::vector<std::string> order = {"finite", "plane", "outliers", "normals", "segment", "select",
                                          "sample", "shape", "check", "reach", "score", "robust"};
  for (const auto& s : order) std::printf(" %s |", s.c_str());
  std::printf("\n|---|");
  for (std::size_t i = 0; i < order.size(); ++i) std::printf("---|");
  std::printf("\n");
  for (auto& [name, row] : stage_rows) {
    std::printf("| %s |", name.c_str());
    for (const auto& s : order)
      row.stages.count(s) ? std::printf(" %.1f |", median(row.stages[s])) : std::printf(" - |");
    std::printf("\n");
  }
  std::printf(
      "\nHeap allocations (malloc and its family: operator new's, Eigen's, TBB's) in one more "
      "frame of "
      "the warm stream at 2 threads (calls, MB asked):\n\n"
      "| frame | segments calls | segments MB | best grasp calls | best grasp MB "
      "|\n|---|---|---|---|---|\n");
  for (const auto& [name, row] : stage_rows)
    std::printf("| %s | %zu | %.1f | %zu | %.1f |\n", name.c_str(), row.seg_alloc.calls, double(row.seg_alloc.bytes) / 1048576.0,
                row.grasp_alloc.calls, double(row.grasp_alloc.bytes) / 1048576.0);
}
