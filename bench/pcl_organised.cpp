#include "pcl_organised.hpp"

#include <pcl/features/integral_image_normal.h>
#include <pcl/segmentation/euclidean_cluster_comparator.h>
#include <pcl/segmentation/organized_connected_component_segmentation.h>
#include <pcl/segmentation/organized_multi_plane_segmentation.h>

#include <memory>
#include <set>

namespace uwgrasp::bench {

pcl::PointCloud<PclPoint>::Ptr to_pcl_organised(const Cloud& c) {
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

namespace {
// Integral-image normals, then the planes of at least 10,000 points with their pixel labels;
// `others` gets the labels of every other component.
pcl::PointCloud<pcl::Label>::Ptr planes_of(const pcl::PointCloud<PclPoint>::Ptr& cloud,
                                           std::set<std::uint32_t>& others) {
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
  for (std::size_t i = 0; i < label_indices.size(); ++i)
    if (label_indices[i].indices.size() <= 10000) others.insert(std::uint32_t(i));
  return labels;
}
}  // namespace

std::vector<std::int32_t> pcl_organised_chain(const pcl::PointCloud<PclPoint>::Ptr& cloud) {
  // PCL 1.13's EuclideanClusterComparator joins two points only when both labels ARE in its
  // "exclude" set (euclidean_cluster_comparator.h, compare()), so it is given the labels that
  // are not planes: what its tutorials mean by excluding the planes.
  auto others = std::make_shared<std::set<std::uint32_t>>();
  const auto labels = planes_of(cloud, *others);
  pcl::EuclideanClusterComparator<PclPoint, pcl::Label>::Ptr comp(
      new pcl::EuclideanClusterComparator<PclPoint, pcl::Label>);
  comp->setInputCloud(cloud);
  comp->setLabels(labels);
  comp->setExcludeLabels(others);
  comp->setDistanceThreshold(0.01f, false);
  pcl::PointCloud<pcl::Label> clusters;
  std::vector<pcl::PointIndices> cluster_indices;
  pcl::OrganizedConnectedComponentSegmentation<PclPoint, pcl::Label> seg(comp);
  seg.setInputCloud(cloud);
  seg.segment(clusters, cluster_indices);
  std::vector<std::int32_t> out(cloud->size(), -1);
  std::int32_t next = 0;
  for (const auto& c : cluster_indices) {
    if (c.indices.size() < 50) continue;
    for (const auto i : c.indices) out[std::size_t(i)] = next;
    ++next;
  }
  return out;
}

}  // namespace uwgrasp::bench
