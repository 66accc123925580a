#pragma once
// grasps.json (INTERFACE.md): the detector's result with the full effective config and seed.
#include <nlohmann/json.hpp>
#include <string>

#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"

namespace uwgrasp::io {

// Poses are in the camera optical frame ("frame"); each grasp also carries its level-frame pose
// ("level") and the vehicle pose T_LB in the level frame. Fields the engine does not compute yet
// (the vehicle score and hold cost) are null.
nlohmann::json grasps_to_json(const grasp::Detection& d, const Config& cfg,
                              const std::string& input, const std::string& version);

// Writes the JSON atomically (no partial file), two-space indented, newline-terminated.
void write_json(const std::string& path, const nlohmann::json& j);

}  // namespace uwgrasp::io
