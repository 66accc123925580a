#pragma once
// Internal to camera/: OpenCV's calibration files (what cv::FileStorage writes, YAML or XML) and
// the number lists of ROS's camera_info, read without trusting the file.
#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace uwgrasp::camera {

// Whether `text` starts as FileStorage's files do ("%YAML" or "<?xml").
bool opencv_storage(const std::string& text);

// An OpenCV calibration file: YAML is read by yaml-cpp (OpenCV 4.6's YAML parser loops forever
// on some malformed text, found by fuzz/), XML by FileStorage after a well-formedness check
// (xml_check.hpp).
struct Storage {
  std::string file;
  YAML::Node yaml;                     // the top mapping of a YAML file
  std::optional<cv::FileStorage> xml;  // an XML file
};

// Throws Error naming `file` for control bytes, malformed YAML or XML, or a YAML file whose top
// level is not a mapping.
Storage open_storage(const std::string& text, const std::string& file);

// The first of `names` present, as a flat list of doubles (row by row). Matrices are at most
// 16 x 16, and their data must fill rows x cols; throws Error naming the key otherwise.
std::optional<std::vector<double>> storage_matrix(const Storage& s, std::initializer_list<const char*> names);

// image_width and image_height, or image_size / imageSize as [width, height].
std::pair<int, int> storage_size(const Storage& s);

// YAML::Load, its exceptions as one Error naming `file`.
YAML::Node load_yaml(const std::string& text, const std::string& file);

// The numbers of a YAML list, or of a {rows, cols, data} mapping's data; Error naming `key`
// when it is neither or holds something that is not a number.
std::vector<double> numbers(const YAML::Node& node, const std::string& file, const std::string& key);

// An integer; Error naming `key` when missing or not an integer.
int integer(const YAML::Node& n, const std::string& file, const std::string& key);

}  // namespace uwgrasp::camera
