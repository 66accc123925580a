#include "uwgrasp/io/ply_check.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
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
