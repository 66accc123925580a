#pragma once
// Structural checks of PCD and PLY headers before PCL reads the file: PCL's readers can crash on
// garbage, so uwgrasp rejects malformed or truncated files with an Error first.
#include <string>

namespace uwgrasp::io {

// Throws Error naming `path` when the PCD header is malformed, inconsistent, or the data section
// is shorter than the header announces.
void check_pcd(const std::string& path);

// True when PCL would read the start of the data section of the PCD file `path` as more header
// lines (check_pcd then refuses it): the writer chooses another encoding.
bool pcd_body_reads_as_header(const std::string& path);

// Throws Error naming `path` when the file does not start like a PLY file with an end_header.
void check_ply(const std::string& path);

}  // namespace uwgrasp::io
