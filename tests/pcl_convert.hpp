#pragma once
// Cloud -> PCL point clouds, for comparing against PCL's implementations.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::test {

inline pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl_xyz(const Cloud& c) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr out(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : c.points) out->push_back({p.x(), p.y(), p.z()});
  out->sensor_origin_ = Eigen::Vector4f(c.viewpoint.x(), c.viewpoint.y(), c.viewpoint.z(), 0);
  return out;
}

inline pcl::PointCloud<pcl::PointXYZRGB>::Ptr to_pcl_rgb(const Cloud& c) {
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr out(new pcl::PointCloud<pcl::PointXYZRGB>);
  for (std::size_t i = 0; i < c.size(); ++i) {
    pcl::PointXYZRGB p(c.colors[i].r, c.colors[i].g, c.colors[i].b);
    p.x = c.points[i].x(), p.y = c.points[i].y(), p.z = c.points[i].z();
    out->push_back(p);
  }
  return out;
}

inline pcl::PointCloud<pcl::Normal>::Ptr to_pcl_normals(const Cloud& c) {
  pcl::PointCloud<pcl::Normal>::Ptr out(new pcl::PointCloud<pcl::Normal>);
  for (std::size_t i = 0; i < c.size(); ++i)
    out->push_back(pcl::Normal(c.normals[i].x(), c.normals[i].y(), c.normals[i].z(),
                               c.curvature[i]));
  return out;
}

}  // namespace uwgrasp::test
