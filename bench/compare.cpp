// bench/compare: uwgrasp and PCL on the same inputs in one process. Prints the median time of
// each stage over repeated runs and the ratio PCL / uwgrasp, as a markdown table.
//   compare [--repeats N] [--threads N]
#include <pcl/features/normal_3d.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/region_growing.h>
#include <pcl/segmentation/sac_segmentation.h>
#include <tbb/global_control.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pcl_organised.hpp"
#include "scene.hpp"
#include "uwgrasp/cloud/filters.hpp"
#include "uwgrasp/cloud/normals.hpp"
#include "uwgrasp/cloud/outliers.hpp"
#include "uwgrasp/cloud/ransac.hpp"
#include "uwgrasp/cloud/voxel.hpp"
#include "uwgrasp/io/pcd.hpp"
#include "uwgrasp/segment/pipeline.hpp"

using namespace uwgrasp;
using PclCloud = pcl::PointCloud<pcl::PointXYZ>;

namespace {
int g_repeats = 7;

double median_ms(const std::function<void()>& f) {
  std::vector<double> t;
  for (int r = 0; r < g_repeats; ++r) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

PclCloud::Ptr to_pcl(const Cloud& c) {
  PclCloud::Ptr out(new PclCloud);
  for (const auto& p : c.points) out->push_back({p.x(), p.y(), p.z()});
  return out;
}

pcl::PointCloud<pcl::Normal>::Ptr to_pcl_normals(const Cloud& c) {
  pcl::PointCloud<pcl::Normal>::Ptr out(new pcl::PointCloud<pcl::Normal>);
  for (std::size_t i = 0; i < c.size(); ++i)
    out->push_back(pcl::Normal(c.normals[i].x(), c.normals[i].y(), c.normals[i].z(), c.curvature[i]));
  return out;
}

void row(const char* input, const char* stage, std::size_t n, double pcl_ms, double ours_ms,
         const std::string& output) {
  std::printf("| %s | %s | %zu | %.2f | %.2f | %.1fx | %s |\n", input, stage, n, pcl_ms, ours_ms,
              pcl_ms / ours_ms, output.c_str());
}

void compare_stages(const char* name, const Cloud& raw) {
  const Cloud c = cloud::remove_invalid(raw).cloud;
  const PclCloud::Ptr pc = to_pcl(c);
  {  // voxel grid
    const float leaf = 0.01f;
    std::size_t np = 0, nu = 0;
    const double tp = median_ms([&] {
      pcl::VoxelGrid<pcl::PointXYZ> vg;
      vg.setInputCloud(pc);
      vg.setLeafSize(leaf, leaf, leaf);
      PclCloud out;
      vg.filter(out);
      np = out.size();
    });
    const double tu = median_ms([&] { nu = cloud::voxel_grid(c, {true, leaf, 1}).cloud.size(); });
    row(name, "voxel grid 1 cm", c.size(), tp, tu, std::to_string(np) + " / " + std::to_string(nu) + " voxels");
  }
  {  // statistical outlier removal
    std::size_t np = 0, nu = 0;
    const double tp = median_ms([&] {
      pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
      sor.setInputCloud(pc);
      sor.setMeanK(10);
      sor.setStddevMulThresh(1.0);
      pcl::Indices kept;
      sor.filter(kept);
      np = kept.size();
    });
    const double tu = median_ms([&] { nu = cloud::remove_outliers(c, {true, 10, 1.0}).indices.size(); });
    row(name, "outliers k=10", c.size(), tp, tu, std::to_string(np) + " / " + std::to_string(nu) + " kept");
  }
  {  // RANSAC plane
    std::size_t np = 0, nu = 0;
    cloud::PlaneConfig cfg;
    cfg.max_iterations = 20;
    const double tp = median_ms([&] {
      pcl::SACSegmentation<pcl::PointXYZ> seg;
      seg.setOptimizeCoefficients(true);
      seg.setModelType(pcl::SACMODEL_PLANE);
      seg.setMethodType(pcl::SAC_RANSAC);
      seg.setDistanceThreshold(cfg.distance);
      seg.setMaxIterations(int(cfg.max_iterations));
      seg.setInputCloud(pc);
      pcl::PointIndices inl;
      pcl::ModelCoefficients m;
      seg.segment(inl, m);
      np = inl.indices.size();
    });
    const double tu = median_ms([&] { nu = cloud::fit_plane(c, cfg, 1).inliers.size(); });
    row(name, "RANSAC plane (20 it, refine)", c.size(), tp, tu, std::to_string(np) + " / " + std::to_string(nu) + " inliers");
  }
  {  // normals
    Cloud with = c;
    const double tp = median_ms([&] {
      pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
      ne.setInputCloud(pc);
      ne.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
      ne.setKSearch(20);
      pcl::PointCloud<pcl::Normal> out;
      ne.compute(out);
    });
    const double tomp = median_ms([&] {
      pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> ne(0);
      ne.setInputCloud(pc);
      ne.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
      ne.setKSearch(20);
      pcl::PointCloud<pcl::Normal> out;
      ne.compute(out);
    });
    const double tu = median_ms([&] { cloud::compute_normals(with, {20, 0}); });
    row(name, "normals k=20", c.size(), tp, tu, "same normals (tests: 99 % within 2 deg)");
    row(name, "normals k=20 vs PCL OMP", c.size(), tomp, tu, "PCL's OpenMP variant");
  }
}

void compare_region_growing(const char* name, const Cloud& raw) {
  // As in the pipeline: the plane removed, normals on what is left.
  StageTimer t;
  cloud::PreprocessConfig pre;
  pre.outliers.enabled = false;
  const Cloud c = cloud::preprocess(raw, pre, 1, t).cloud;
  segment::RegionConfig r;
  r.distance = 0.0f;  // PCL's RegionGrowing has no distance criterion
  std::size_t np = 0, nu = 0;
  const double tp = median_ms([&] {
    pcl::RegionGrowing<pcl::PointXYZ, pcl::Normal> rg;
    rg.setInputCloud(to_pcl(c));
    rg.setInputNormals(to_pcl_normals(c));
    rg.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
    rg.setNumberOfNeighbours(int(r.k));
    rg.setSmoothnessThreshold(r.angle_deg / 180.0f * float(M_PI));
    rg.setCurvatureThreshold(r.curvature);
    rg.setMinClusterSize(int(r.min_size));
    std::vector<pcl::PointIndices> cl;
    rg.extract(cl);
    np = cl.size();
  });
  const double tu = median_ms([&] { nu = segment::grow_regions(c, r, {}).segments.size(); });
  row(name, "region growing k=30", c.size(), tp, tu, std::to_string(np) + " / " + std::to_string(nu) + " segments");
}

// An organised frame: PCL's organised chain (pcl_organised.hpp) against uwgrasp's organised path
// from the raw frame to segments.
void organised_chain(const char* name, const Cloud& frame) {
  const auto pcl_frame = bench::to_pcl_organised(frame);
  std::size_t np = 0, nu = 0;
  const double tp = median_ms([&] {
    const auto labels = bench::pcl_organised_chain(pcl_frame);
    np = labels.empty() ? 0 : std::size_t(*std::max_element(labels.begin(), labels.end()) + 1);
  });
  const double tu = median_ms([&] { nu = segment::segment_scene(frame, {}, {}, 1).info.size(); });
  row(name, "organised frame -> segments", frame.size(), tp, tu,
      std::to_string(np) + " clusters / " + std::to_string(nu) + " segments");
}

void whole_chain(const char* name, const Cloud& raw) {
  segment::Scene s;
  const double tu = median_ms([&] { s = segment::segment_scene(raw, {}, {}, 1); });
  std::printf("| %s | whole chain (default config) | %zu | - | %.2f | - | %zu segments;", name,
              raw.size(), tu, s.info.size());
  for (const auto& st : s.timer.stages()) std::printf(" %s %.1f", st.name.c_str(), st.ms);
  std::printf(" ms |\n");
}
}  // namespace

int main(int argc, char** argv) {
  // PCL's OpenMP stages leave their threads spinning after each parallel region, which takes a
  // core from the next stage (measured: uwgrasp's voxel grid 20 ms instead of 13 ms). libgomp reads
  // OMP_WAIT_POLICY when it loads, so set it and start again.
  if (!std::getenv("OMP_WAIT_POLICY")) {
    setenv("OMP_WAIT_POLICY", "passive", 1);
    execv("/proc/self/exe", argv);
  }
  int threads = 0;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeats")) g_repeats = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--threads")) threads = std::atoi(argv[++i]);
  }
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  std::printf("median of %d runs; PCL stages are single-threaded unless noted, uwgrasp uses %s\n\n",
              g_repeats, threads > 0 ? (std::to_string(threads) + " threads").c_str() : "all cores");
  std::printf("| input | stage | points in | PCL ms | uwgrasp ms | PCL/uwgrasp | output PCL / uwgrasp |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  const Cloud scene = bench::seafloor_scene();
  compare_stages("seafloor 400k", scene);
  compare_region_growing("seafloor 400k", scene);
  const std::string mug = std::string(UWGRASP_DATA_DIR) + "/clouds/table_scene_mug_stereo_textured.pcd";
  Cloud mug_cloud;
  if (std::filesystem::exists(mug)) {
    mug_cloud = io::load_cloud(mug);
    compare_stages("mug stereo", mug_cloud);
    compare_region_growing("mug stereo", mug_cloud);
  }
  organised_chain("seafloor 640 x 480 frame", bench::seafloor_scene(640, 480));
  if (!mug_cloud.empty()) organised_chain("mug stereo", mug_cloud);
  whole_chain("seafloor 400k", scene);
  if (!mug_cloud.empty()) whole_chain("mug stereo", mug_cloud);
  return 0;
}
