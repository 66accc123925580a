// The text formats: config YAML and --set overrides, scenes, truth.yaml, grasps.json and
// calibration files.
#include <string>
#include <string_view>

#include "fuzz/inputs.hpp"
#include "uwgrasp/camera/files.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/grasps_json.hpp"
#include "uwgrasp/io/scene_yaml.hpp"

namespace uwgrasp::fuzz {

namespace {
std::string text(Bytes in) { return std::string(reinterpret_cast<const char*>(in.data()), in.size()); }

// Runs f and treats uwgrasp::Error, the documented refusal, as a normal return.
template <typename F>
void refused_or_ok(F&& f) {
  try {
    f();
  } catch (const Error&) {
  }
}

// "yaml\n%%\nkey=value\nkey=value": the file, then one --set override per line.
void split_config(const std::string& all, std::string& yaml, std::vector<std::string>& sets) {
  const std::size_t cut = all.find("\n%%\n");
  yaml = all.substr(0, cut);
  if (cut == std::string::npos) return;
  std::string_view rest(all);
  rest.remove_prefix(cut + 4);
  while (!rest.empty()) {
    const std::size_t nl = rest.find('\n');
    sets.emplace_back(rest.substr(0, nl));
    if (nl == std::string_view::npos) break;
    rest.remove_prefix(nl + 1);
  }
}

// OpenCV reads a calibration file by its extension: XML when the text starts with '<'.
std::string calibration_file(Bytes in) {
  std::size_t i = 0;
  while (i < in.size() && (in[i] == ' ' || in[i] == '\n' || in[i] == '\r' || in[i] == '\t')) ++i;
  return scratch_file(in, i < in.size() && in[i] == '<' ? ".xml" : ".yaml");
}
}  // namespace

void config(Bytes in) {
  std::string yaml;
  std::vector<std::string> sets;
  split_config(text(in), yaml, sets);
  io::Config cfg;
  try {
    cfg = io::parse_config(yaml, "fuzz.yaml", sets);
  } catch (const Error&) {
    return;
  }
  // An accepted config written out must read back as itself.
  const std::string once = io::to_yaml(cfg);
  const std::string twice = io::to_yaml(io::parse_config(once, "round trip"));
  if (once != twice) throw Invariant("config changed in a to_yaml round trip");
}

void scene(Bytes in) {
  refused_or_ok([&] { io::parse_scene(text(in), "fuzz.yaml", "/nonexistent-uwgrasp-fuzz"); });
}

void truth(Bytes in) {
  refused_or_ok([&] { io::load_truth(scratch_file(in, ".yaml")); });
}

void grasps_json(Bytes in) {
  const std::string path = scratch_file(in, ".json");
  refused_or_ok([&] { io::read_grasp_list(path, ""); });
  refused_or_ok([&] { io::read_grasp(path, 1, ""); });
}

void camera(Bytes in) {
  refused_or_ok([&] { camera::read_camera(calibration_file(in)); });
}

void stereo(Bytes in) {
  refused_or_ok([&] { camera::read_stereo(calibration_file(in)); });
}

}  // namespace uwgrasp::fuzz
