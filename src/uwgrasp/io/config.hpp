#pragma once
// The effective configuration: compiled-in defaults (the thesis's values, mirrored 1:1 in
// config/default.yaml), then a YAML file, then `--set section.key=value` overrides.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "uwgrasp/camera/dense.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/segment/pipeline.hpp"
#include "uwgrasp/sim/camera.hpp"
#include "uwgrasp/sim/water.hpp"
#include "uwgrasp/vehicle/control.hpp"
#include "uwgrasp/vehicle/model.hpp"

namespace uwgrasp::io {

// The simulator's sensor (`simulate`, `demo`, `experiments`); the scene itself is a file or a
// built-in name, and may carry its own water.
struct SimConfig {
  sim::CameraConfig camera;
  std::string water = "clear";  // preset: clear, coastal, turbid
  sim::NoiseConfig noise;
};

// The vehicle that carries the gripper (hold cost, approach simulation). Defaults: the BlueROV2
// Heavy of config/vehicle/bluerov2_heavy.yaml, whose comments cite every value.
struct VehicleConfig {
  vehicle::VehicleParams params{.thrusters = vehicle::heavy_thrusters()};  // always eight
  Eigen::Vector3d current = Eigen::Vector3d::Zero();  // constant ocean current in L, m/s
  vehicle::ControlConfig control;
};

struct Config {
  std::uint64_t seed = 1;      // every random choice derives from it
  std::uint32_t threads = 0;   // 0: all cores
  camera::DenseConfig stereo;  // stereo pairs to clouds (stereo, detect --stereo)
  cloud::PreprocessConfig preprocess;
  segment::SegmentConfig segment;
  grasp::GraspConfig grasp;
  SimConfig sim;
  VehicleConfig vehicle;
};

// Throws Error naming the file (or "--set") and the dotted key for an unknown key, a value of
// the wrong type or a value out of range; a missing or malformed file is an Error too.
Config load_config(const std::string& path, const std::vector<std::string>& overrides = {});
Config parse_config(const std::string& yaml, const std::string& source,
                    const std::vector<std::string>& overrides = {});
// Applies "a.b.c=value" overrides to an existing config, then binds the vehicle's hold cost to
// grasp.score.hold_cost (throws Error when the thrusters cannot produce every wrench).
void apply_overrides(Config& cfg, const std::vector<std::string>& overrides);

std::string to_yaml(const Config& cfg);
nlohmann::json to_json(const Config& cfg);

}  // namespace uwgrasp::io
