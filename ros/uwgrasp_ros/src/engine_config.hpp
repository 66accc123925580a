#pragma once
// C++20 callers only (the CLI): an Engine from an effective config built elsewhere.
#include "engine.hpp"
#include "uwgrasp/io/config.hpp"

namespace uwgrasp_ros {

Engine make_engine(const uwgrasp::io::Config& cfg);

}  // namespace uwgrasp_ros
