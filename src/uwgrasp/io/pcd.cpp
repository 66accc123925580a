#include "uwgrasp/io/pcd.hpp"

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/atomic_file.hpp"
#include "uwgrasp/io/header_check.hpp"
#include "uwgrasp/io/pcl_blob.hpp"

namespace uwgrasp::io {

namespace {
std::string extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return e;
}

// PCL reports problems on stderr itself; uwgrasp reports them as one Error line instead.
void quiet_pcl() { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); }

void check_readable(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(path + ": no such file");
  if (fs::is_directory(path, ec)) throw Error(path + ": is a directory, not a cloud file");
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(path + ": cannot open for reading");
  if (fs::file_size(path, ec) == 0) throw Error(path + ": file is empty");
}
// ASCII at 9 significant digits reads back every float bit for bit (PCL's default 8 does not).
int write_as(const std::string& tmp, const pcl::PCLPointCloud2& blob, const Eigen::Vector4f& origin,
             const Eigen::Quaternionf& orient, PcdFormat format) {
  pcl::PCDWriter w;
  switch (format) {
    case PcdFormat::ascii: return w.writeASCII(tmp, blob, origin, orient, 9);
    case PcdFormat::binary: return w.writeBinary(tmp, blob, origin, orient);
    case PcdFormat::binary_compressed: return w.writeBinaryCompressed(tmp, blob, origin, orient);
  }
  return -1;
}

// Binary data can begin like a header line, which PCL would parse as one (header_check.cpp): a
// file is then written in the next encoding, binary -> binary_compressed -> ascii, so that every
// cloud written reads back.
int write_pcd(const std::string& tmp, const pcl::PCLPointCloud2& blob, const Eigen::Vector4f& origin,
              const Eigen::Quaternionf& orient, PcdFormat format) {
  int rc = write_as(tmp, blob, origin, orient, format);
  while (rc >= 0 && format != PcdFormat::ascii && pcd_body_reads_as_header(tmp)) {
    format = format == PcdFormat::binary ? PcdFormat::binary_compressed : PcdFormat::ascii;
    rc = write_as(tmp, blob, origin, orient, format);
  }
  return rc;
}
}  // namespace

Cloud load_cloud(const std::string& path) {
  quiet_pcl();
  check_readable(path);
  const std::string ext = extension(path);
  pcl::PCLPointCloud2 blob;
  Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  int rc = -1;
  try {
    if (ext == ".pcd") {
      check_pcd(path);
      pcl::PCDReader reader;
      int version = 0;
      rc = reader.read(path, blob, origin, orientation, version);
    } else if (ext == ".ply") {
      check_ply(path);
      pcl::PLYReader reader;
      int version = 0;
      rc = reader.read(path, blob, origin, orientation, version);
    } else {
      throw Error(path + ": unsupported extension '" + ext + "' (use .pcd or .ply)");
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path + ": cannot parse (" + e.what() + ")");
  }
  if (rc < 0) throw Error(path + ": malformed or truncated " + ext.substr(1) + " file");
  Cloud c = from_blob(blob, path);
  c.viewpoint = origin.head<3>();
  if (!origin.head<3>().allFinite() || !orientation.coeffs().allFinite() ||
      std::abs(orientation.norm() - 1.0f) > 1e-3f)
    throw Error(path + ": VIEWPOINT is not a finite position and unit quaternion");
  c.orientation = orientation.normalized();
  return c;
}

void save_cloud(const std::string& path, const Cloud& cloud, PcdFormat format) {
  quiet_pcl();
  check_consistent(cloud, path.c_str());
  const std::string ext = extension(path);
  if (ext != ".pcd" && ext != ".ply")
    throw Error(path + ": unsupported extension '" + ext + "' (use .pcd or .ply)");
  const pcl::PCLPointCloud2 blob = to_blob(cloud);
  Eigen::Vector4f origin(cloud.viewpoint.x(), cloud.viewpoint.y(), cloud.viewpoint.z(), 0.0f);
  const Eigen::Quaternionf orient = cloud.orientation;
  write_atomically(path, [&](const std::string& tmp) {
    int rc = 0;
    errno = 0;
    if (ext == ".ply" && cloud.empty()) {
      // PCL's PLY writer refuses an empty cloud; an empty segment is still a file to write.
      std::ofstream out(tmp, std::ios::binary);
      out << "ply\nformat binary_little_endian 1.0\nelement vertex 0\n"
             "property float x\nproperty float y\nproperty float z\nend_header\n";
      out.close();
      if (!out) rc = -1;
    } else if (ext == ".ply") {
      rc = pcl::PLYWriter().write(tmp, blob, origin, orient, true, false);
    } else {
      rc = write_pcd(tmp, blob, origin, orient, 
                     cloud.empty() && format == PcdFormat::binary_compressed ? PcdFormat::binary : format);
    }
    if (rc < 0) throw Error(path + ": cannot write" + reason());
  });
}

}  // namespace uwgrasp::io
