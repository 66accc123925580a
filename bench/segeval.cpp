// bench/segeval: per-object best-segment IoU against the mOSD ground-truth labels
// (label >= 20: one id per object), for uwgrasp's organised and k-d tree paths, for PCL's
// RegionGrowing run with the same parameters on the same preprocessed cloud (same normals, plane
// removed), and for PCL's organised chain on the raw frame. Then how far the two paths' normals
// agree on the points both keep, away from depth edges, on the same frames and the real stereo
// mug frame, and on the analytic seafloor scene, with and without depth noise, against its true
// normals too.
//   segeval [--set section.key=value]...
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/region_growing.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "pcl_organised.hpp"
#include "scene.hpp"
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

// Mean best IoU and the number of objects at >= 0.8, summed over scenes.
struct Tally {
  double sum = 0;
  std::size_t good = 0;
  void add(const std::map<std::uint32_t, double>& ious, double& mean, std::size_t& k) {
    mean = 0, k = 0;
    for (auto [g, v] : ious) mean += v, k += v >= 0.8;
    sum += mean, good += k;
    mean /= double(ious.size());
  }
};

// Whether pixel i's window of `half` pixels lies wholly in the frame, every pixel finite and
// range-continuous with it as the organised path defines it (2 % of the range per pixel step).
bool away_from_edges(const Cloud& in, std::size_t i, int half, float change) {
  const int w = int(in.width), h = int(in.height), u = int(i % in.width), v = int(i / in.width);
  if (u < half || v < half || u + half >= w || v + half >= h || !is_finite(in.points[i])) return false;
  const float r = in.points[i].norm();
  for (int dv = -half; dv <= half; ++dv)
    for (int du = -half; du <= half; ++du) {
      const Eigen::Vector3f& q = in.points[std::size_t((v + dv) * w + u + du)];
      const float ring = float(std::max(std::abs(du), std::abs(dv)));
      if (!is_finite(q) || std::abs(q.norm() - r) > change * ring * r) return false;
    }
  return true;
}

// The share of pixels (both paths keep the point and give it a normal, away from depth edges
// over the organised normal window) whose two normals lie within `deg` of each other (as
// lines: a flipped sign is the same normal), and the median angle.
struct Agreement {
  std::size_t points = 0;
  double share = 0, median_deg = 0;
};
// `b` null: against `truth` (one normal per input pixel), on the points `a` keeps.
Agreement normals_agree(const Cloud& in, const segment::Scene& a, const segment::Scene* b,
                        const cloud::OrganisedConfig& org, double deg,
                        const std::vector<Eigen::Vector3f>* truth = nullptr) {
  std::vector<double> angles;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const auto ia = a.pre.output_of_input[i], ib = b ? b->pre.output_of_input[i] : 0;
    if (ia < 0 || ib < 0 || !away_from_edges(in, i, int(org.normal_half_window), org.depth_change)) continue;
    const Eigen::Vector3f na = a.pre.cloud.normals[std::size_t(ia)];
    const Eigen::Vector3f nb = b ? b->pre.cloud.normals[std::size_t(ib)] : (*truth)[i];
    if (!is_finite(na) || !is_finite(nb)) continue;
    angles.push_back(std::acos(std::min(1.0, double(std::abs(na.normalized().dot(nb.normalized()))))) * 180.0 / M_PI);
  }
  Agreement out;
  out.points = angles.size();
  if (angles.empty()) return out;
  std::size_t within = 0;
  for (const double x : angles) within += x <= deg;
  out.share = double(within) / double(angles.size());
  std::nth_element(angles.begin(), angles.begin() + std::ptrdiff_t(angles.size() / 2), angles.end());
  out.median_deg = angles[angles.size() / 2];
  return out;
}

// The analytic seafloor scene (bench/scene.hpp: boxes on a plane, 640 x 480) without depth noise
// and with the noise of a stereo rig (sigma = noise z^2): the two paths' normals against each
// other and each against the true faces' normals.
void analytic_normals(const io::Config& cfg, const io::Config& kd_cfg) {
  std::printf("\nOn the analytic seafloor scene (640 x 480, boxes on a plane), the same comparison and each "
              "path against the true normals (the faces'), on the points each keeps away from depth edges:\n\n");
  std::printf("| depth noise (sigma at 1 m) | organised vs k-d tree: within 5 deg | median | organised vs truth: "
              "within 5 deg | median | k-d tree vs truth: within 5 deg | median |\n|---|---|---|---|---|---|---|\n");
  for (const float noise : {0.0f, 0.0005f, 0.001f, 0.002f}) {
    std::vector<Eigen::Vector3f> truth;
    const Cloud in = bench::seafloor_scene(640, 480, noise, 1, &truth);
    const segment::Scene s = segment::segment_scene(in, cfg.preprocess, cfg.segment, cfg.seed);
    const segment::Scene kd = segment::segment_scene(in, kd_cfg.preprocess, kd_cfg.segment, cfg.seed);
    const cloud::OrganisedConfig& org = cfg.preprocess.organised;
    const Agreement ab = normals_agree(in, s, &kd, org, 5.0), at = normals_agree(in, s, nullptr, org, 5.0, &truth),
                    bt = normals_agree(in, kd, nullptr, org, 5.0, &truth);
    std::printf("| %.1f mm | %.1f %% | %.2f | %.1f %% | %.2f | %.1f %% | %.2f |\n", 1000.0f * noise, 100.0 * ab.share,
                ab.median_deg, 100.0 * at.share, at.median_deg, 100.0 * bt.share, bt.median_deg);
  }
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> sets;
  for (int i = 1; i + 1 < argc; ++i)
    if (!std::strcmp(argv[i], "--set")) sets.push_back(argv[++i]);
  const io::Config cfg = io::load_config("", sets);
  io::Config kd_cfg = cfg;
  kd_cfg.preprocess.organised.enabled = false;
  const std::string dir = std::string(UWGRASP_DATA_DIR) + "/clouds/";
  std::printf("Mean best IoU per object (objects at IoU >= 0.8): uwgrasp's organised path (the default on "
              "these frames), its k-d tree path, PCL RegionGrowing on the organised path's cloud and "
              "normals, PCL's organised chain on the raw frame.\n\n");
  std::printf("| scene | objects | organised | k-d tree | PCL RegionGrowing | PCL organised chain |\n");
  std::printf("|---|---|---|---|---|---|\n");
  Tally tally[4];
  std::size_t n = 0;
  for (const char* name : {"mOSD_learn0", "mOSD_learn17", "mOSD_learn25", "mOSD_learn33"}) {
    const std::string path = dir + name + ".pcd";
    if (!std::filesystem::exists(path)) {
      std::printf("| %s | missing | | | | |\n", name);
      continue;
    }
    const Cloud in = io::load_cloud(path);
    const segment::Scene s = segment::segment_scene(in, cfg.preprocess, cfg.segment, cfg.seed);
    const segment::Scene kd = segment::segment_scene(in, kd_cfg.preprocess, kd_cfg.segment, cfg.seed);
    const std::map<std::uint32_t, double> ious[4] = {
        best_iou(in.labels, segment::input_labels(s)), best_iou(in.labels, segment::input_labels(kd)),
        best_iou(in.labels, pcl_labels(s, cfg.segment.region)),
        best_iou(in.labels, bench::pcl_organised_chain(bench::to_pcl_organised(in)))};
    const std::size_t k = ious[0].size();
    std::printf("| %s | %zu |", name, k);
    for (int m = 0; m < 4; ++m) {
      double mean;
      std::size_t good;
      tally[m].add(ious[m], mean, good);
      std::printf(" %.3f (%zu/%zu) |", mean, good, k);
    }
    std::printf("\n");
    n += k;
  }
  if (n == 0) return 0;
  std::printf("| all | %zu |", n);
  for (const auto& t : tally)
    std::printf(" %.3f (%.0f %%) |", t.sum / double(n), 100.0 * double(t.good) / double(n));
  std::printf("\n\nNormals of the organised path against the k-d tree path's, on the points both keep, away from "
              "depth edges (the organised normal window wholly in the frame and range-continuous):\n\n");
  std::printf("| frame | points compared | within 5 deg | median angle deg |\n|---|---|---|---|\n");
  for (const char* name : {"mOSD_learn0", "mOSD_learn17", "mOSD_learn25", "mOSD_learn33", "table_scene_mug_stereo_textured"}) {
    const std::string path = dir + name + ".pcd";
    if (!std::filesystem::exists(path)) continue;
    const Cloud in = io::load_cloud(path);
    const segment::Scene s = segment::segment_scene(in, cfg.preprocess, cfg.segment, cfg.seed);
    const segment::Scene kd = segment::segment_scene(in, kd_cfg.preprocess, kd_cfg.segment, cfg.seed);
    const Agreement g = normals_agree(in, s, &kd, cfg.preprocess.organised, 5.0);
    std::printf("| %s | %zu | %.1f %% | %.2f |\n", name, g.points, 100.0 * g.share, g.median_deg);
  }
  analytic_normals(cfg, kd_cfg);
  return 0;
}
