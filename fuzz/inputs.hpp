#pragma once
// One fuzz input fed to one of uwgrasp's parsers of outside input. Each function returns
// normally when the parser accepts the input or refuses it with uwgrasp::Error (the documented
// way to refuse); anything else escapes: another exception type, a failed invariant (Invariant,
// thrown here when an accepted input does not survive a write and read back), or a crash the
// sanitizers catch. The libFuzzer targets in this folder and the regression test
// (tests/fuzz/test_regressions.cpp) call the same functions.
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace uwgrasp::fuzz {

using Bytes = std::span<const std::uint8_t>;

struct Invariant : std::logic_error {
  using std::logic_error::logic_error;
};

void pcd(Bytes in);          // load_cloud on a .pcd file, then a binary round trip
void ply(Bytes in);          // load_cloud on a .ply file, then a binary round trip
void config(Bytes in);       // YAML config, then "--set" lines after a line "%%"; to_yaml round trip
void scene(Bytes in);        // scene YAML (objects, parts, poses, water, port)
void truth(Bytes in);        // truth.yaml as `evaluate` reads it
void grasps_json(Bytes in);  // grasps.json as `evaluate` and `approach` read it
void camera(Bytes in);       // camera calibration, YAML or (starting with '<') XML
void stereo(Bytes in);       // stereo rig calibration, YAML or XML
void png(Bytes in);          // a PNG file read as depth and stereo images are, then a round trip

struct Target {
  const char* name;
  void (*run)(Bytes);
};
// Every target above, by name (the folders of fuzz/regressions/ and of the corpora).
const std::vector<Target>& targets();

// Writes `in` to a per-process scratch file with extension `ext` and returns its path.
std::string scratch_file(Bytes in, const std::string& ext);

}  // namespace uwgrasp::fuzz
