#pragma once
// The report's parts: each writes its section of report.md (and its PNGs).
#include <sstream>
#include <string>
#include <vector>

#include "experiments/experiments.hpp"

namespace uwgrasp::experiments {

// printf into a string (report cells).
std::string fmt(const char* format, ...) __attribute__((format(printf, 1, 2)));
// "median unit (min-max)" with `format` for each number; "-" when empty.
std::string median_range(const std::vector<double>& v, const char* unit, const char* format);

void write_overview(std::ostringstream& md, const std::vector<ConditionResult>& results);
void write_segmentation(std::ostringstream& md, const ConditionResult& r);  // tables 8.1, 8.2
void write_sampling(std::ostringstream& md, const ConditionResult& r);      // table 8.3
void write_checking(std::ostringstream& md, const ConditionResult& r);      // table 8.4
void write_weights(std::ostringstream& md, const ConditionResult& r);       // table 8.5
void write_judged(std::ostringstream& md, const ConditionResult& r);        // judged top grasps
// The vehicle: hold cost against roll, pitch and yaw, q_o against q_v over the thesis's
// sampling range (DIR/vehicle_qo_qv.png), and the top grasps of one condition.
void write_vehicle_model(std::ostringstream& md, const io::Config& cfg, const std::string& dir);
void write_vehicle_runs(std::ostringstream& md, const ConditionResult& r);
// Figures 8.13-8.16 as DIR/<condition>_fig8_*.png, with their tables.
void write_figures(std::ostringstream& md, const ConditionResult& r, const std::string& dir);

}  // namespace uwgrasp::experiments
