#pragma once
// C++20 callers only (the CLI): an Engine from an effective config built elsewhere.
#include "engine.hpp"
#include "uwgrasp/io/config.hpp"

namespace uwgrasp_ros {

Engine make_engine(const uwgrasp::io::Config& cfg);

Pose7 pose7(const uwgrasp::Pose& T);
PlainCloud plain_cloud(const uwgrasp::Cloud& c);

}  // namespace uwgrasp_ros
