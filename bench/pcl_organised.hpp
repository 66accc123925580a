// PCL's organised chain as its tutorials run it, for the benches that compare against it:
// IntegralImageNormalEstimation (covariance, depth change 0.02, smoothing 10) +
// OrganizedMultiPlaneSegmentation (planes of 10,000 points, 2 deg, 2 cm, refined) +
// OrganizedConnectedComponentSegmentation (Euclidean comparator, 1 cm, planes excluded).
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdint>
#include <vector>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::bench {

using PclPoint = pcl::PointXYZRGBA;

// The frame as PCL's organised cloud (same width, height and pixel order; NaN stays NaN).
pcl::PointCloud<PclPoint>::Ptr to_pcl_organised(const Cloud& c);

// The chain on one frame: each pixel's cluster (clusters of at least 50 points, numbered from
// 0), -1 for planes, small clusters and invalid pixels.
std::vector<std::int32_t> pcl_organised_chain(const pcl::PointCloud<PclPoint>::Ptr& cloud);

}  // namespace uwgrasp::bench
