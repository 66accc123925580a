#pragma once
// Internal to io/: the PLY header as header_check.cpp reads it, and the check of its range_grid.
#include <istream>
#include <map>
#include <string>
#include <vector>

namespace uwgrasp::io {

struct PlyElement {
  std::string name;
  std::size_t count = 0, row_bytes = 0;  // row_bytes: of the scalar properties
  bool has_list = false;
  std::vector<std::string> properties;
  std::vector<std::string> types;  // a scalar type, or "list COUNT_TYPE ITEM_TYPE"
};

// Bytes of a PLY scalar type; 0 for a name that is not one.
std::size_t ply_type_size(const std::string& t);

// The vertex colour must be whole (red, green, blue, alpha in a row, uchar); the obj_info grid
// (num_cols x num_rows) must hold the vertices, and equal them without a range_grid. Throw Error.
void check_ply_colour(const std::string& path, const std::vector<PlyElement>& elements);
void check_ply_grid(const std::string& path, const std::map<std::string, std::string>& info,
                    const std::vector<PlyElement>& elements);

// PCL fills an organised cloud's cells from the range_grid element: each cell lists at most one
// vertex, which must exist. A cell naming a vertex past the end, or several, leaves PCL reading
// garbage into the cloud (found by fuzz/). `f` stands at the first byte of the body; throws
// Error naming `path` for such a grid or a body too short for its elements.
void check_ply_range_grid(const std::string& path, std::istream& f, const std::string& format,
                          const std::vector<PlyElement>& elements);

}  // namespace uwgrasp::io
