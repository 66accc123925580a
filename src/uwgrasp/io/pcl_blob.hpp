#pragma once
// Conversion between Cloud and PCL's generic pcl::PCLPointCloud2 (private to io/).
#include <pcl/PCLPointCloud2.h>

#include <string>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::io {

// `source` names the file in error messages.
Cloud from_blob(const pcl::PCLPointCloud2& blob, const std::string& source);
pcl::PCLPointCloud2 to_blob(const Cloud& cloud);

}  // namespace uwgrasp::io
