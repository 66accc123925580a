#include "uwgrasp/camera/storage.hpp"

#include <cmath>

#include "uwgrasp/camera/xml_check.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::camera {

namespace {
// OpenCV's FileStorage parser reads NUL and other control bytes past the end of its buffers
// (crashes in OpenCV 4.6, found by fuzz/): a calibration file must be text.
void check_text(const std::string& text, const std::string& file) {
  for (const char ch : text) {
    const auto u = static_cast<unsigned char>(ch);
    if (u < 0x20 && u != '\t' && u != '\n' && u != '\r')
      throw Error(file + ": not a text file (control byte " + std::to_string(int(u)) + ")");
  }
}

// FileStorage's "%YAML:1.0" is not YAML's directive form: that line becomes an empty one, so
// yaml-cpp's line numbers stay the file's.
YAML::Node opencv_yaml(const std::string& text, const std::string& file) {
  const std::size_t eol = text.find('\n', text.find_first_not_of(" \t\r\n"));
  const YAML::Node root = load_yaml(eol == std::string::npos ? std::string() : text.substr(eol), file);
  if (!root.IsMap()) throw Error(file + ": an OpenCV YAML file must hold named values (a mapping)");
  return root;
}

cv::FileStorage opencv_xml(const std::string& text, const std::string& file) {
  check_xml(text, file);
  try {
    cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
    if (!fs.isOpened()) throw Error(file + ": not a readable OpenCV XML file");
    return fs;
  } catch (const std::exception&) {  // cv::Exception, and std::length_error from its parser
    throw Error(file + ": not a readable OpenCV XML file");
  }
}

[[noreturn]] void not_a_matrix(const std::string& file, const char* name) {
  throw Error(file + ": " + name + " is not a matrix of 1 to 16 rows and columns");
}

// Calibration matrices are at most 3 x 4: OpenCV would allocate whatever rows x cols a file
// claims before reading its data (tens of GB, found by fuzz/).
std::optional<std::vector<double>> xml_matrix(const cv::FileStorage& fs, const std::string& file,
                                              std::initializer_list<const char*> names) {
  for (const char* n : names) {
    const cv::FileNode node = fs[n];
    if (node.empty()) continue;
    if (node.isMap()) {
      const cv::FileNode rows = node["rows"], cols = node["cols"];
      if (!rows.isInt() || !cols.isInt() || int(rows) < 1 || int(cols) < 1 || int(rows) > 16 || int(cols) > 16)
        not_a_matrix(file, n);
    } else if (node.isSeq() && node.size() > 256) {
      throw Error(file + ": " + n + " has " + std::to_string(node.size()) + " numbers");
    }
    cv::Mat m;
    node >> m;
    m.convertTo(m, CV_64F);
    return std::vector<double>(m.begin<double>(), m.end<double>());
  }
  return std::nullopt;
}

std::optional<std::vector<double>> yaml_matrix(const YAML::Node& root, const std::string& file,
                                               std::initializer_list<const char*> names) {
  for (const char* n : names) {
    const YAML::Node node = root[n];
    if (!node) continue;
    std::vector<double> v = numbers(node, file, n);
    if (node.IsMap()) {
      const int rows = integer(node["rows"], file, std::string(n) + ".rows");
      const int cols = integer(node["cols"], file, std::string(n) + ".cols");
      if (rows < 1 || cols < 1 || rows > 16 || cols > 16) not_a_matrix(file, n);
      if (v.size() != std::size_t(rows * cols))
        throw Error(file + ": " + n + " holds " + std::to_string(v.size()) + " numbers, not rows x cols = " +
                    std::to_string(rows * cols));
    } else if (v.size() > 256) {
      throw Error(file + ": " + n + " has " + std::to_string(v.size()) + " numbers");
    }
    return v;
  }
  return std::nullopt;
}
}  // namespace

bool opencv_storage(const std::string& text) {
  const auto start = text.find_first_not_of(" \t\r\n");
  return start != std::string::npos &&
         (text.compare(start, 5, "%YAML") == 0 || text.compare(start, 5, "<?xml") == 0);
}

Storage open_storage(const std::string& text, const std::string& file) {
  check_text(text, file);
  Storage s{file, {}, std::nullopt};
  if (text.compare(text.find_first_not_of(" \t\r\n"), 5, "<?xml") == 0) s.xml = opencv_xml(text, file);
  else s.yaml = opencv_yaml(text, file);
  return s;
}

std::optional<std::vector<double>> storage_matrix(const Storage& s, std::initializer_list<const char*> names) {
  return s.xml ? xml_matrix(*s.xml, s.file, names) : yaml_matrix(s.yaml, s.file, names);
}

std::pair<int, int> storage_size(const Storage& s) {
  if (s.xml) {
    const cv::FileStorage& fs = *s.xml;
    if (!fs["image_width"].empty() && !fs["image_height"].empty())
      return {int(fs["image_width"]), int(fs["image_height"])};
    for (const char* n : {"image_size", "imageSize"}) {
      if (fs[n].empty()) continue;
      std::vector<int> v;
      fs[n] >> v;
      if (v.size() == 2) return {v[0], v[1]};
    }
  } else {
    const YAML::Node& y = s.yaml;
    if (y["image_width"] && y["image_height"])
      return {integer(y["image_width"], s.file, "image_width"), integer(y["image_height"], s.file, "image_height")};
    for (const char* n : {"image_size", "imageSize"}) {
      if (!y[n]) continue;
      const std::vector<double> v = numbers(y[n], s.file, n);
      const auto whole = [](double x) { return std::abs(x) < 1e9 && x == std::floor(x); };
      if (v.size() != 2 || !whole(v[0]) || !whole(v[1])) throw Error(s.file + ": " + n + " must be [width, height]");
      return {int(v[0]), int(v[1])};
    }
  }
  throw Error(s.file + ": missing the image size (image_width and image_height, or image_size)");
}

YAML::Node load_yaml(const std::string& text, const std::string& file) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(file + ": not valid YAML: " + e.what());
  }
}

std::vector<double> numbers(const YAML::Node& node, const std::string& file, const std::string& key) {
  const YAML::Node list = node.IsMap() ? node["data"] : node;
  if (!list || !list.IsSequence())
    throw Error(file + ": " + key + " must be a list of numbers (or {rows, cols, data})");
  std::vector<double> out;
  for (const auto& v : list) {
    try {
      out.push_back(v.as<double>());
    } catch (const YAML::Exception&) {
      throw Error(file + ": " + key + " holds a value that is not a number");
    }
  }
  return out;
}

int integer(const YAML::Node& n, const std::string& file, const std::string& key) {
  if (!n) throw Error(file + ": missing " + key);
  try {
    return n.as<int>();
  } catch (const YAML::Exception&) {
    throw Error(file + ": " + key + " must be an integer");
  }
}

}  // namespace uwgrasp::camera
