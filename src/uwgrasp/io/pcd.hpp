#pragma once
// Point cloud files: PCD (ascii, binary, binary_compressed) and PLY, read and written through
// PCL's io with every field the pipeline uses: x y z, rgb/rgba, normal_x/y/z, curvature, label.
#include <string>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::io {

enum class PcdFormat { ascii, binary, binary_compressed };

// Loads a .pcd or .ply file. Throws Error naming the file for a missing or unreadable file, a
// malformed or truncated one, or one without x, y and z fields.
Cloud load_cloud(const std::string& path);

// Writes .pcd (in `format`) or .ply (binary); the file appears only when complete.
void save_cloud(const std::string& path, const Cloud& cloud,
                PcdFormat format = PcdFormat::binary_compressed);

}  // namespace uwgrasp::io
