// bench/frame: raw 640x480 frame -> segments and -> best grasp, median over repeated frames in
// one process (as a camera stream would run), at 1 and 2 threads; the k-d tree path on the same
// frames; and PCL's organised chain (IntegralImageNormalEstimation +
// OrganizedMultiPlaneSegmentation + OrganizedConnectedComponentSegmentation) on the same frames.
//   frame [--repeats N]   (default 20)
#include <pcl/features/integral_image_normal.h>
#include <pcl/segmentation/euclidean_cluster_comparator.h>
#include <pcl/segmentation/organized_connected_component_segmentation.h>
#include <pcl/segmentation/organized_multi_plane_segmentation.h>
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

#include "scene.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/memory.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/pcd.hpp"

using namespace uwgrasp;
using PclPoint = pcl::PointXYZRGBA;

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

pcl::PointCloud<PclPoint>::Ptr to_pcl(const Cloud& c) {
  pcl::PointCloud<PclPoint>::Ptr out(new pcl::PointCloud<PclPoint>);
  out->width = c.width, out->height = c.height, out->is_dense = false;
  out->points.resize(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) {
    PclPoint& p = out->points[i];
    p.x = c.points[i].x(), p.y = c.points[i].y(), p.z = c.points[i].z();
    if (c.has_colors()) p.r = c.colors[i].r, p.g = c.colors[i].g, p.b = c.colors[i].b;
  }
  return out;
}

// PCL's organised chain as its tutorials run it: integral-image normals, planes of at least
// 10,000 points, then Euclidean clusters of what is not a plane. Returns the clusters found.
std::size_t pcl_chain(const pcl::PointCloud<PclPoint>::Ptr& cloud) {
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  pcl::IntegralImageNormalEstimation<PclPoint, pcl::Normal> ne;
  ne.setNormalEstimationMethod(ne.COVARIANCE_MATRIX);
  ne.setMaxDepthChangeFactor(0.02f);
  ne.setNormalSmoothingSize(10.0f);
  ne.setInputCloud(cloud);
  ne.compute(*normals);
  pcl::OrganizedMultiPlaneSegmentation<PclPoint, pcl::Normal, pcl::Label> mps;
  mps.setMinInliers(10000);
  mps.setAngularThreshold(0.017453 * 2.0);
  mps.setDistanceThreshold(0.02);
  mps.setInputNormals(normals);
  mps.setInputCloud(cloud);
  std::vector<pcl::PlanarRegion<PclPoint>, Eigen::aligned_allocator<pcl::PlanarRegion<PclPoint>>> regions;
  std::vector<pcl::ModelCoefficients> coefficients;
  std::vector<pcl::PointIndices> inliers, label_indices, boundaries;
  pcl::PointCloud<pcl::Label>::Ptr labels(new pcl::PointCloud<pcl::Label>);
  mps.segmentAndRefine(regions, coefficients, inliers, labels, label_indices, boundaries);
  auto planes = std::make_shared<std::set<std::uint32_t>>();
  for (std::size_t i = 0; i < label_indices.size(); ++i)
    if (label_indices[i].indices.size() > 10000) planes->insert(std::uint32_t(i));
  pcl::EuclideanClusterComparator<PclPoint, pcl::Label>::Ptr comp(
      new pcl::EuclideanClusterComparator<PclPoint, pcl::Label>);
  comp->setInputCloud(cloud);
  comp->setLabels(labels);
  comp->setExcludeLabels(planes);
  comp->setDistanceThreshold(0.01f, false);
  pcl::PointCloud<pcl::Label> clusters;
  std::vector<pcl::PointIndices> cluster_indices;
  pcl::OrganizedConnectedComponentSegmentation<PclPoint, pcl::Label> seg(comp);
  seg.setInputCloud(cloud);
  seg.segment(clusters, cluster_indices);
  std::size_t n = 0;
  for (const auto& c : cluster_indices) n += c.indices.size() >= 50;
  return n;
}

struct Row {
  double segments = 0, grasp = 0, kd_segments = 0;
  std::map<std::string, std::vector<double>> stages;
};

Row run_uwgrasp(const Cloud& frame, io::Config cfg, int repeats) {
  Row row;
  std::vector<double> seg, grasp, kd;
  for (int r = 0; r < repeats; ++r) {
    seg.push_back(time_ms([&] { segment::segment_scene(frame, cfg.preprocess, cfg.segment, cfg.seed); }));
    grasp::Detection d;
    grasp.push_back(time_ms([&] { d = grasp::detect(frame, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed); }));
    for (const auto& st : d.timer.stages()) row.stages[st.name].push_back(st.ms);
  }
  cfg.preprocess.organised.enabled = false;
  for (int r = 0; r < std::max(3, repeats / 4); ++r)
    kd.push_back(time_ms([&] { segment::segment_scene(frame, cfg.preprocess, cfg.segment, cfg.seed); }));
  row.segments = median(seg), row.grasp = median(grasp), row.kd_segments = median(kd);
  return row;
}
}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();  // a stream of frames: the first frame's buffers serve the rest
  int repeats = 20;
  for (int i = 1; i + 1 < argc; ++i)
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::max(1, std::atoi(argv[++i]));
  io::Config cfg = io::load_config("", {"segment.object.by=largest"});
  std::vector<std::pair<std::string, Cloud>> frames;
  const std::string dir = std::string(UWGRASP_DATA_DIR) + "/clouds/";
  for (const char* f : {"table_scene_mug_stereo_textured", "mOSD_learn0", "mOSD_learn17",
                        "mOSD_learn25", "mOSD_learn33"})
    if (std::filesystem::exists(dir + f + ".pcd")) frames.emplace_back(f, io::load_cloud(dir + f + ".pcd"));
  frames.emplace_back("simulated thesis scene", bench::seafloor_scene(640, 480));
  std::printf("| frame | threads | segments ms | best grasp ms | k-d tree path segments ms | "
              "PCL organised chain ms | PCL / uwgrasp (segments) |\n|---|---|---|---|---|---|---|\n");
  std::vector<std::pair<std::string, Row>> stage_rows;
  for (const auto& [name, frame] : frames) {
    const auto pcl_cloud = to_pcl(frame);
    std::vector<double> pcl_ms;
    for (int r = 0; r < repeats; ++r) pcl_ms.push_back(time_ms([&] { pcl_chain(pcl_cloud); }));
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
}
