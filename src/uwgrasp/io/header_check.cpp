#include "uwgrasp/io/header_check.hpp"
#include "uwgrasp/io/ply_check.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::io {

namespace {
using Words = std::vector<std::string>;

Words split(const std::string& line) {
  std::istringstream s(line);
  Words w;
  for (std::string x; s >> x;) w.push_back(x);
  return w;
}

[[noreturn]] void bad(const std::string& path, const std::string& what) {
  throw Error(path + ": malformed pcd file (" + what + ")");
}

std::size_t number(const std::string& path, const std::string& key, const std::string& v) {
  if (v.empty() || v.find_first_not_of("0123456789") != std::string::npos)
    bad(path, key + " '" + v + "' is not a non-negative integer");
  if (v.size() > 10) bad(path, key + " '" + v + "' is too large");  // at most 2^32 - 1 points
  return static_cast<std::size_t>(std::stoull(v));
}

struct Header {
  std::map<std::string, Words> entries;
  std::streamoff data_offset = 0;
};

// A header word as text a terminal shows: other bytes as \xNN (a PNG's magic, say).
std::string printable(const std::string& w) {
  std::string out;
  for (const char ch : w.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(ch);
    if (u >= 0x20 && u < 0x7f) {
      out += ch;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      out += buf;
    }
  }
  return out;
}

// PCL's reader misreads a header with a line it does not know (a null read in PCL 1.13, found
// by fuzz/), so only the PCD v0.7 keys are let through, each once.
bool pcd_key(const std::string& k) {
  for (const char* known : {"VERSION", "FIELDS", "SIZE", "TYPE", "COUNT", "WIDTH", "HEIGHT", "VIEWPOINT", "POINTS", "DATA"})
    if (k == known) return true;
  return false;
}

Header read_header(const std::string& path, std::ifstream& f) {
  Header h;
  std::string line;
  for (int n = 0; n < 64 && std::getline(f, line); ++n) {
    const Words w = split(line);
    // PCL skips an empty line but reads a null pointer on one of blank space only (found by fuzz/).
    if (w.empty() && !line.empty()) bad(path, "a header line of blank space only");
    if (w.empty() || w[0][0] == '#') continue;
    if (!pcd_key(w[0])) bad(path, "unknown header line '" + printable(w[0]) + "'");
    if (h.entries.count(w[0])) bad(path, "two " + w[0] + " lines");
    h.entries[w[0]] = Words(w.begin() + 1, w.end());
    if (w[0] == "DATA") {
      h.data_offset = f.tellg();
      return h;
    }
  }
  bad(path, "no DATA line in the header");
}

void check_fields(const std::string& path, const Header& h, std::size_t& point_size) {
  for (const char* k : {"FIELDS", "SIZE", "TYPE", "WIDTH", "HEIGHT", "POINTS"})
    if (!h.entries.count(k)) bad(path, std::string("no ") + k + " line");
  const Words& fields = h.entries.at("FIELDS");
  const Words& size = h.entries.at("SIZE");
  const Words& type = h.entries.at("TYPE");
  Words count(fields.size(), "1");
  if (h.entries.count("COUNT")) count = h.entries.at("COUNT");
  if (fields.empty() || size.size() != fields.size() || type.size() != fields.size() ||
      count.size() != fields.size())
    bad(path, "FIELDS, SIZE, TYPE and COUNT disagree in length");
  point_size = 0;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::size_t s = number(path, "SIZE", size[i]), c = number(path, "COUNT", count[i]);
    if (s != 1 && s != 2 && s != 4 && s != 8) bad(path, "SIZE " + size[i] + " of " + fields[i]);
    if (type[i] != "I" && type[i] != "U" && type[i] != "F") bad(path, "TYPE " + type[i]);
    if (type[i] == "F" && s != 4 && s != 8) bad(path, "float field " + fields[i] + " of size " + size[i]);
    if (c == 0 || c > 100000) bad(path, "COUNT " + count[i]);
    point_size += s * c;
  }
}

std::size_t single(const std::string& path, const Header& h, const char* key) {
  const Words& w = h.entries.at(key);
  if (w.size() != 1) bad(path, std::string(key) + " needs one value");
  return number(path, key, w[0]);
}

// PCL 1.13's header reader goes on after the DATA line: it skips empty lines, comments ('#') and
// VERSION lines, and parses the next line as a header line when it starts with a header key (by
// prefix). Binary data that happens to begin "COLUMNS" or "FIELDS", at once or after such lines,
// is then parsed as fields (a 100 TB allocation, found by fuzz/). Returns that line's first word,
// or "" when PCL reads the data where it starts (a body beginning '#', one binary file in 256, does).
std::string header_like_body(std::ifstream& f, std::streamoff data_offset) {
  f.clear();
  f.seekg(data_offset);
  std::string line, found;
  while (found.empty() && std::getline(f, line)) {
    if (line.empty()) continue;
    const Words w = split(line);
    if (w.empty()) break;
    const std::string& t = w[0];
    if (t[0] == '#' || t.rfind("VERSION", 0) == 0) continue;
    for (const char* k : {"FIELDS", "COLUMNS", "SIZE", "TYPE", "COUNT", "WIDTH", "HEIGHT", "VIEWPOINT", "POINTS", "DATA"})
      if (t.rfind(k, 0) == 0) found = t;
    break;
  }
  f.clear();
  f.seekg(data_offset);  // the readers below start at the data
  return found;
}
}  // namespace

bool pcd_body_reads_as_header(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return !header_like_body(f, read_header(path, f).data_offset).empty();
}

void check_pcd(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  const Header h = read_header(path, f);
  const std::string t = header_like_body(f, h.data_offset);
  if (!t.empty()) bad(path, "the data after DATA begins like a header line ('" + printable(t) + "')");
  std::size_t point_size = 0;
  check_fields(path, h, point_size);
  const std::size_t width = single(path, h, "WIDTH"), height = single(path, h, "HEIGHT");
  const std::size_t points = single(path, h, "POINTS");
  // HEIGHT 0 with a WIDTH is no layout (PCL writes 1 for an unorganised cloud): its 0 points
  // would pass WIDTH * HEIGHT == POINTS and leave a cloud whose layout claims WIDTH points.
  if (height == 0 && width != 0)
    bad(path, "HEIGHT 0 with WIDTH " + std::to_string(width) + " (1 for an unorganised cloud)");
  if ((height != 0 && width > points / height + 1) || width * height != points)
    bad(path, "WIDTH * HEIGHT != POINTS");
  if (points > 0xffffffffULL) bad(path, "POINTS " + std::to_string(points) + " is beyond 2^32 - 1");
  const Words& data = h.entries.at("DATA");
  if (data.size() != 1) bad(path, "DATA needs one value");
  const auto file_size = static_cast<std::size_t>(std::filesystem::file_size(path));
  const auto body = file_size - static_cast<std::size_t>(h.data_offset);
  if (data[0] == "binary") {
    if (body < points * point_size)
      throw Error(path + ": truncated pcd file (" + std::to_string(body) + " data bytes, " +
                  std::to_string(points * point_size) + " expected)");
  } else if (data[0] == "binary_compressed") {
    std::uint32_t sizes[2] = {0, 0};
    if (points == 0) return;
    if (body < 8 || !f.read(reinterpret_cast<char*>(sizes), 8))
      throw Error(path + ": truncated pcd file (no compressed block)");
    if (sizes[0] > body - 8)
      throw Error(path + ": truncated pcd file (compressed block of " + std::to_string(sizes[0]) +
                  " bytes, " + std::to_string(body - 8) + " present)");
    if (sizes[1] != points * point_size) bad(path, "uncompressed size disagrees with POINTS");
  } else if (data[0] == "ascii") {
    // A point takes at least two bytes a field ("0 "): bound what PCL would reserve up front.
    const std::size_t fields = h.entries.at("FIELDS").size();
    if (points > body / (2 * fields))
      throw Error(path + ": truncated pcd file (" + std::to_string(points) + " points declared, " +
                  std::to_string(body) + " bytes of ascii data hold at most " +
                  std::to_string(body / (2 * fields)) + ")");
  } else {
    bad(path, "DATA '" + data[0] + "' is not ascii, binary or binary_compressed");
  }
}

std::size_t ply_type_size(const std::string& t) {
  static const std::map<std::string, std::size_t> sizes = {
      {"char", 1},  {"uchar", 1},  {"int8", 1},  {"uint8", 1},  {"short", 2},   {"ushort", 2},
      {"int16", 2}, {"uint16", 2}, {"int", 4},   {"uint", 4},   {"int32", 4},   {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(t);
  return it == sizes.end() ? 0 : it->second;
}

namespace {
[[noreturn]] void bad_ply(const std::string& path, const std::string& what) {
  throw Error(path + ": malformed ply file (" + what + ")");
}

void ply_property(const std::string& path, const Words& w, std::vector<PlyElement>& elements) {
  if (elements.empty()) bad_ply(path, "a property before any element");
  PlyElement& e = elements.back();
  const bool list = w.size() >= 2 && w[1] == "list";
  if (w.size() != (list ? 5u : 3u))
    bad_ply(path, "a property line is not 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
  if (list && (ply_type_size(w[2]) == 0 || w[2] == "float" || w[2] == "double" || w[2] == "float32" ||
               w[2] == "float64" || ply_type_size(w[3]) == 0))
    bad_ply(path, "list property " + w[4] + " of types " + w[2] + " " + w[3]);
  if (!list && ply_type_size(w[1]) == 0) bad_ply(path, "property type '" + w[1] + "'");
  // PCL's reader asserts on a list in the vertex element (found by fuzz/): points have none.
  if (list && e.name == "vertex") bad_ply(path, "vertex property " + w.back() + " is a list");
  const std::string& name = w.back();
  for (const auto& p : e.properties)
    if (p == name) bad_ply(path, "two properties named '" + name + "' in element " + e.name);
  e.properties.push_back(name);
  e.types.push_back(list ? "list " + w[2] + " " + w[3] : w[1]);
  e.has_list = e.has_list || list;
  if (!list) e.row_bytes += ply_type_size(w[1]);
}

// After end_header (f just past it): the header's elements against each other and against the
// data that follows.
void check_ply_data(const std::string& path, std::ifstream& f, const std::string& format,
                    const std::map<std::string, std::string>& info,
                    const std::vector<PlyElement>& elements) {
  if (format.empty()) bad_ply(path, "no format line");
  const auto data_offset = static_cast<std::size_t>(f.tellg());
  check_ply_grid(path, info, elements);
  check_ply_colour(path, elements);
  check_ply_range_grid(path, f, format, elements);
  f.clear();
  const auto body = std::filesystem::file_size(path) - data_offset;
  std::size_t need = 0;  // bytes (binary) or lines (ascii) the leading list-free elements take
  for (const auto& e : elements) {
    if (e.has_list) break;
    need += format == "ascii" ? e.count * 2 : e.count * e.row_bytes;
  }
  if (body < need)
    throw Error(path + ": truncated ply file (" + std::to_string(body) + " data bytes, at least " +
                std::to_string(need) + " expected)");
}

}  // namespace

// PCL's PLY reader asserts (aborts) on headers it misreads, such as a line it does not know or
// two properties of one name (found by fuzz/): the header is read strictly here first, and the
// body must hold the elements it declares.
void check_ply(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::string line;
  if (!std::getline(f, line) || (line != "ply" && line != "ply\r"))
    throw Error(path + ": malformed ply file (its first line is not 'ply')");
  std::string format;
  std::vector<PlyElement> elements;
  std::map<std::string, std::string> info;  // obj_info KEY VALUE
  for (int n = 0; n < 200 && std::getline(f, line); ++n) {
    // PCL matches some keywords at the very start of the line and others after a split: a line
    // that starts with blank space reaches an assert in its obj_info handler (found by fuzz/).
    if (!line.empty() && static_cast<unsigned char>(line[0]) <= ' ')
      bad_ply(path, "a header line starts with blank space or a control byte");
    const Words w = split(line);
    // PCL sizes organised clouds from these two (by prefix, taking the last): each once, alone.
    if (w.size() >= 2 && w[0] == "obj_info" && (w[1].rfind("num_cols", 0) == 0 || w[1].rfind("num_rows", 0) == 0)) {
      const std::string key = w[1].substr(0, 8);
      if (w.size() != 3 || info.count(key)) bad_ply(path, "obj_info " + printable(w[1]) + " is not one 'obj_info KEY N' line");
      info[key] = w[2];
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") return check_ply_data(path, f, format, info, elements);
    if (w[0] == "format") {
      if (!format.empty() || w.size() != 3 || w[2] != "1.0" ||
          (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
        bad_ply(path, "format line '" + line + "'");
      format = w[1];
    } else if (w[0] == "element") {
      if (w.size() != 3 || w[2].empty() || w[2].size() > 10 || w[2].find_first_not_of("0123456789") != std::string::npos)
        bad_ply(path, "element line '" + line + "' (want 'element NAME COUNT', COUNT below 2^32)");
      elements.push_back({w[1], std::stoull(w[2]), 0, false, {}, {}});
    } else if (w[0] == "property") {
      ply_property(path, w, elements);
    } else {
      bad_ply(path, "unknown header line '" + printable(w[0]) + "'");
    }
  }
  throw Error(path + ": malformed ply file (no end_header)");
}

}  // namespace uwgrasp::io
