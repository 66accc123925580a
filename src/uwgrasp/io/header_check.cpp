#include "uwgrasp/io/header_check.hpp"

#include <cstdint>
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

Header read_header(const std::string& path, std::ifstream& f) {
  Header h;
  std::string line;
  for (int n = 0; n < 64 && std::getline(f, line); ++n) {
    const Words w = split(line);
    if (w.empty() || w[0][0] == '#') continue;
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
}  // namespace

void check_pcd(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  const Header h = read_header(path, f);
  std::size_t point_size = 0;
  check_fields(path, h, point_size);
  const std::size_t width = single(path, h, "WIDTH"), height = single(path, h, "HEIGHT");
  const std::size_t points = single(path, h, "POINTS");
  if ((height != 0 && width > points / height + 1) || width * height != points)
    bad(path, "WIDTH * HEIGHT != POINTS");
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
  } else if (data[0] != "ascii") {
    bad(path, "DATA '" + data[0] + "' is not ascii, binary or binary_compressed");
  }
}

void check_ply(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::string line;
  if (!std::getline(f, line) || line.rfind("ply", 0) != 0)
    throw Error(path + ": malformed ply file (it does not start with 'ply')");
  for (int n = 0; n < 200 && std::getline(f, line); ++n)
    if (line.rfind("end_header", 0) == 0) return;
  throw Error(path + ": malformed ply file (no end_header)");
}

}  // namespace uwgrasp::io
