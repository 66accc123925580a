// bench/segeval: per-object best-segment IoU against the mOSD ground-truth labels
// (label >= 20: one id per object), for uwgrasp and for PCL's RegionGrowing run with the same
// parameters on the same preprocessed cloud (same normals, plane removed).
//   segeval [--set section.key=value]...
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/region_growing.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/pcd.hpp"
#include "uwgrasp/segment/pipeline.hpp"

using namespace uwgrasp;

namespace {
// Best IoU of each ground-truth object (label >= 20) with any predicted segment (-1: none).
std::map<std::uint32_t, double> best_iou(const std::vector<std::uint32_t>& truth,
                                         const std::vector<std::int32_t>& pred) {
  std::map<std::uint32_t, std::size_t> gsize;
  std::map<std::int32_t, std::size_t> psize;
  std::map<std::pair<std::uint32_t, std::int32_t>, std::size_t> inter;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i] >= 20) ++gsize[truth[i]];
    if (pred[i] >= 0) ++psize[pred[i]];
    if (truth[i] >= 20 && pred[i] >= 0) ++inter[{truth[i], pred[i]}];
  }
  std::map<std::uint32_t, double> best;
  for (auto [g, n] : gsize) best[g] = 0.0;
  for (auto [key, n] : inter) {
    const double iou = double(n) / double(gsize[key.first] + psize[key.second] - n);
    best[key.first] = std::max(best[key.first], iou);
  }
  return best;
}

std::vector<std::int32_t> pcl_labels(const segment::Scene& s, const segment::RegionConfig& r) {
  const Cloud& c = s.pre.cloud;
  pcl::PointCloud<pcl::PointXYZ>::Ptr pts(new pcl::PointCloud<pcl::PointXYZ>);
  pcl::PointCloud<pcl::Normal>::Ptr nrm(new pcl::PointCloud<pcl::Normal>);
  pcl::IndicesPtr valid(new pcl::Indices);
  for (std::size_t i = 0; i < c.size(); ++i) {
    pts->push_back({c.points[i].x(), c.points[i].y(), c.points[i].z()});
    nrm->push_back(pcl::Normal(c.normals[i].x(), c.normals[i].y(), c.normals[i].z(), c.curvature[i]));
    if (is_finite(c.normals[i])) valid->push_back(int(i));
  }
  pcl::RegionGrowing<pcl::PointXYZ, pcl::Normal> rg;
  rg.setInputCloud(pts);
  rg.setIndices(valid);
  rg.setInputNormals(nrm);
  rg.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
  rg.setNumberOfNeighbours(int(r.k));
  rg.setSmoothnessThreshold(r.angle_deg / 180.0f * float(M_PI));
  rg.setCurvatureThreshold(r.curvature);
  rg.setMinClusterSize(int(r.min_size));
  rg.setMaxClusterSize(int(std::min<std::uint32_t>(r.max_size, 0x7fffffff)));
  std::vector<pcl::PointIndices> clusters;
  rg.extract(clusters);
  std::vector<std::int32_t> lab(c.size(), -1);
  for (std::size_t k = 0; k < clusters.size(); ++k)
    for (auto i : clusters[k].indices) lab[std::size_t(i)] = std::int32_t(k);
  std::vector<std::int32_t> out(s.pre.output_of_input.size(), -1);
  for (std::size_t i = 0; i < out.size(); ++i)
    if (s.pre.output_of_input[i] >= 0) out[i] = lab[std::size_t(s.pre.output_of_input[i])];
  return out;
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> sets;
  for (int i = 1; i + 1 < argc; ++i)
    if (!std::strcmp(argv[i], "--set")) sets.push_back(argv[++i]);
  const io::Config cfg = io::load_config("", sets);
  const std::string dir = std::string(UWGRASP_DATA_DIR) + "/clouds/";
  std::printf("| scene | objects | uwgrasp mean IoU | uwgrasp IoU >= 0.8 | PCL mean IoU | PCL IoU >= 0.8 |\n");
  std::printf("|---|---|---|---|---|---|\n");
  double su = 0, sp = 0;
  std::size_t n = 0, gu = 0, gp = 0;
  for (const char* name : {"mOSD_learn0", "mOSD_learn17", "mOSD_learn25", "mOSD_learn33"}) {
    const std::string path = dir + name + ".pcd";
    if (!std::filesystem::exists(path)) {
      std::printf("| %s | missing | | | | |\n", name);
      continue;
    }
    const Cloud in = io::load_cloud(path);
    const segment::Scene s = segment::segment_scene(in, cfg.preprocess, cfg.segment, cfg.seed);
    const auto ours = best_iou(in.labels, segment::input_labels(s));
    const auto ref = best_iou(in.labels, pcl_labels(s, cfg.segment.region));
    double mu = 0, mp = 0;
    std::size_t ku = 0, kp = 0;
    for (auto [g, v] : ours) mu += v, ku += v >= 0.8;
    for (auto [g, v] : ref) mp += v, kp += v >= 0.8;
    const std::size_t k = ours.size();
    std::printf("| %s | %zu | %.3f | %zu/%zu | %.3f | %zu/%zu |\n", name, k, mu / double(k), ku, k,
                mp / double(k), kp, k);
    su += mu, sp += mp, n += k, gu += ku, gp += kp;
  }
  if (n > 0)
    std::printf("| all | %zu | %.3f | %.0f %% | %.3f | %.0f %% |\n", n, su / double(n),
                100.0 * double(gu) / double(n), sp / double(n), 100.0 * double(gp) / double(n));
  return 0;
}
