#include "uwgrasp/io/ply_check.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::io {

namespace {
[[noreturn]] void bad_grid(const std::string& path, const std::string& what) {
  throw Error(path + ": malformed ply file (" + what + ")");
}

// One integer of PLY type `type` from a binary body, in the file's byte order.
long long read_integer(std::istream& f, const std::string& type, bool big_endian) {
  const std::size_t n = ply_type_size(type);
  unsigned char b[8] = {};
  if (n == 0 || n > 8 || !f.read(reinterpret_cast<char*>(b), std::streamsize(n))) return -1;
  if (big_endian) std::reverse(b, b + n);
  std::uint64_t u = 0;
  std::memcpy(&u, b, n);  // little-endian host
  const bool is_signed = type == "char" || type == "int8" || type == "short" || type == "int16" ||
                         type == "int" || type == "int32";
  if (is_signed && n < 8 && (u >> (8 * n - 1)) & 1) u |= ~std::uint64_t(0) << (8 * n);
  return static_cast<long long>(u);
}

void check_cell(const std::string& path, long long n, long long index, std::size_t vertices) {
  if (n < 0 || n > 1) bad_grid(path, "a range_grid cell lists " + std::to_string(n) + " vertices");
  if (n == 1 && (index < 0 || static_cast<unsigned long long>(index) >= vertices))
    bad_grid(path, "a range_grid cell names vertex " + std::to_string(index) + " of " + std::to_string(vertices));
}

// One row of an element with lists; returns false when the body ends early.
bool binary_row(const std::string& path, std::istream& f, const PlyElement& e, bool big, bool grid,
                std::size_t vertices) {
  for (const std::string& t : e.types) {
    if (t.rfind("list ", 0) != 0) {
      f.ignore(std::streamsize(ply_type_size(t)));
      continue;
    }
    std::istringstream types(t.substr(5));
    std::string count_type, item_type;
    types >> count_type >> item_type;
    const long long n = read_integer(f, count_type, big);
    if (n < 0) return false;
    if (grid) {
      check_cell(path, n, n == 1 ? read_integer(f, item_type, big) : 0, vertices);
    } else {
      f.ignore(std::streamsize(n) * std::streamsize(ply_type_size(item_type)));
    }
  }
  return bool(f);
}
}  // namespace

// PCL packs red, green and blue (and alpha) into one field as it meets them: a vertex with only
// some of them, in another order or of another type is read into the wrong bytes (found by
// fuzz/: the points change), so colour must come whole, in order, one uchar a channel.
void check_ply_colour(const std::string& path, const std::vector<PlyElement>& elements) {
  for (const auto& e : elements) {
    if (e.name != "vertex") continue;
    const auto& p = e.properties;
    const auto at = std::find(p.begin(), p.end(), "red");
    std::size_t i = std::size_t(at - p.begin());
    const bool any = std::any_of(p.begin(), p.end(), [](const std::string& n) {
      return n == "red" || n == "green" || n == "blue" || n == "alpha";
    });
    if (!any) return;
    const bool whole = i + 2 < p.size() && p[i + 1] == "green" && p[i + 2] == "blue" &&
                       (std::count(p.begin(), p.end(), "alpha") == 0 || (i + 3 < p.size() && p[i + 3] == "alpha"));
    if (!whole) bad_grid(path, "vertex colour is not red, green, blue (and alpha) in a row");
    for (std::size_t k = i; k < p.size() && k < i + 4; ++k)
      if ((k < i + 3 || p[k] == "alpha") && e.types[k] != "uchar" && e.types[k] != "uint8")
        bad_grid(path, "colour property " + p[k] + " is " + e.types[k] + ", not uchar");
  }
}

// PCL sizes an organised cloud from obj_info num_cols x num_rows and writes the vertices into
// it: fewer cells than vertices is a write past its end (an assert), so the grid must hold them.
void check_ply_grid(const std::string& path, const std::map<std::string, std::string>& info,
                    const std::vector<PlyElement>& elements) {
  std::size_t vertices = 0, grid = 0, cells[2] = {0, 0};
  bool has_grid = false;
  for (const auto& e : elements) {
    if (e.name == "vertex") vertices = e.count;
    if (e.name == "range_grid") grid = e.count, has_grid = true;
  }
  const char* keys[2] = {"num_cols", "num_rows"};
  for (int k = 0; k < 2; ++k) {
    const auto it = info.find(keys[k]);
    if (it == info.end()) continue;
    const std::string& v = it->second;
    if (v.empty() || v.size() > 9 || v.find_first_not_of("0123456789") != std::string::npos)
      bad_grid(path, std::string("obj_info ") + keys[k] + " '" + v + "'");
    cells[k] = std::stoull(v);
  }
  if (info.count("num_cols") != info.count("num_rows"))
    bad_grid(path, "obj_info gives one of num_cols and num_rows without the other");
  // Without a range_grid PCL fills the grid with the vertices in order: a grid larger than them
  // leaves cells it never writes (garbage points, found by fuzz/), a smaller one overflows.
  if (info.count("num_cols") && (has_grid ? cells[0] * cells[1] < vertices : cells[0] * cells[1] != vertices))
    bad_grid(path, "obj_info num_cols x num_rows (" + std::to_string(cells[0] * cells[1]) + ") " +
                      (has_grid ? "below" : "is not") + " the " + std::to_string(vertices) + " vertices");
  if (has_grid && grid != cells[0] * cells[1])
    bad_grid(path, "range_grid of " + std::to_string(grid) + " cells, obj_info gives " +
                      std::to_string(cells[0] * cells[1]));
}
void check_ply_range_grid(const std::string& path, std::istream& f, const std::string& format,
                          const std::vector<PlyElement>& elements) {
  const auto grid = std::find_if(elements.begin(), elements.end(), [](const PlyElement& e) { return e.name == "range_grid"; });
  if (grid == elements.end()) return;
  std::size_t vertices = 0;
  for (const auto& e : elements)
    if (e.name == "vertex") vertices = e.count;
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  for (auto e = elements.begin(); e != grid + 1; ++e) {
    const bool is_grid = e == grid;
    if (!ascii && !e->has_list && !is_grid) {
      f.ignore(std::streamsize(e->count * e->row_bytes));
      if (!f) bad_grid(path, "the body ends inside element " + e->name);
      continue;
    }
    for (std::size_t r = 0; r < e->count; ++r) {
      bool ok = true;
      if (ascii) {
        std::string line;
        ok = bool(std::getline(f, line));
        long long n = 0, index = 0;
        if (ok && is_grid) {
          std::istringstream in(line);
          if (!(in >> n) || (n == 1 && !(in >> index))) bad_grid(path, "a range_grid line is not 'N [INDEX]'");
          check_cell(path, n, index, vertices);
        }
      } else {
        ok = binary_row(path, f, *e, big, is_grid, vertices);
      }
      if (!ok) bad_grid(path, "the body ends inside element " + e->name);
    }
  }
}

}  // namespace uwgrasp::io
