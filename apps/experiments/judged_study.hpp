#pragma once
// The judged study: the detector with the default settings (or any --config/--set) on scenes
// it was not tuned on, each iteration a new seed (sensor noise, marine snow, sampling), every
// top grasp judged against the full shapes (eval/): top-1 success, robust success, precision@k,
// AP and the outcome mix per scene and water, and how well the detector's own scores predict the
// judged outcome (calibration) over every feasible candidate.
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "experiments/experiments.hpp"
#include "uwgrasp/eval/calibration.hpp"
#include "uwgrasp/eval/evaluate.hpp"
#include "uwgrasp/eval/exists.hpp"

namespace uwgrasp::experiments {

struct JudgedCase {
  std::string scene;  // built-in name or scene file
  std::string water;  // preset; empty: the scene file's own water (else the config's sim.water)
  bool noise = false; // realistic sensor (noise, dropouts, marine snow)
  std::string sensor = "rgbd";  // or "stereo": the pair matched by camera/ into the cloud
  std::string label() const {
    return (water.empty() ? std::string("scene's water") : water) + (sensor == "stereo" ? " stereo" : "") +
           (noise ? "" : " (perfect sensor)");
  }
};

struct JudgedPlan {
  io::Config base;                // the session's config: what the detector runs with
  std::vector<std::string> sets;  // --set overrides (for the report)
  int iterations = 20;
  std::vector<JudgedCase> cases;
  eval::SummaryConfig summary;
  eval::RobustConfig robust;
  bool calibrate = true;          // judge every feasible candidate, not only the top ones
  // The detector is not told the camera's attitude: its mount taken as looking straight ahead
  // and the vehicle as level, as for a frame with no IMU data or mount calibration.
  bool withhold_attitude = false;
  // A seafloor rising ahead by this much (rad): the scene is rendered as it is (objects resting
  // on a floor the vehicle sits parallel to), and the detector is given the vehicle's attitude
  // against gravity, pitched nose-up by the slope, as its IMU would report on such a seafloor.
  double slope = 0.0;
};

// One iteration of one case.
struct JudgedRun {
  std::string error;          // detection stopped with this Error ("" when it ran)
  std::size_t feasible = 0, candidates = 0;  // passed every check, of those drawn
  std::size_t object_points = 0, visible_points = 0;  // detected object vs its visible pixels
  eval::Summary summary;      // over the top grasps
  double robust = std::numeric_limits<double>::quiet_NaN();
  bool has_top1 = false;
  eval::Judgement top1;
  // The detector's own view of its top-1 (runs.csv): predicted friction, robustness on the
  // model, width at closure and whether each contact lies on the camera's points.
  double predicted_mu = std::numeric_limits<double>::quiet_NaN();
  double predicted_robustness = std::numeric_limits<double>::quiet_NaN();
  double predicted_width = std::numeric_limits<double>::quiet_NaN();
  bool contact_seen[2] = {false, false};
  double detect_ms = 0, judge_ms = 0;
  // Stereo: the object's true depth against the matched cloud (median relative error, share of
  // its visible pixels with a depth); NaN for the RGB-D sensor.
  double depth_error = std::numeric_limits<double>::quiet_NaN();
  double completeness = std::numeric_limits<double>::quiet_NaN();
};

// A feasible candidate's own scores beside its judged outcome at the reference mu.
struct ScoredOutcome {
  grasp::Scores scores;
  double mu_required = 0;  // the detector's own antipodal estimate (+inf: none)
  double robustness = 0, force_closure = 0;  // robust mode: on the object's model
  double mu_min = 0;       // the judge's (+inf when it does not close)
  bool holds = false;
};

struct JudgedCaseResult {
  JudgedCase c;
  std::vector<JudgedRun> runs;
  std::vector<ScoredOutcome> scored;  // every feasible candidate of every iteration
  cv::Mat tile;                       // the first iteration's judged grasps on the truth
  double seconds = 0;
  // Whether any grasp of the gripper holds the object (eval/exists.hpp): when none does, "no
  // grasp" is the right answer and counts as a success.
  bool grasp_exists = true;
};

std::vector<JudgedCaseResult> run_judged_study(const JudgedPlan& plan);

// The built-in scenes of real objects (every pose), and of the thesis's objects alone.
std::vector<std::string> held_in_scenes();
std::vector<std::string> thesis_object_scenes();

// DIR/report.md with tables, calibration and one figure per object; `command` made it.
void write_judged_report(const std::string& dir, const std::vector<JudgedCaseResult>& results,
                         const JudgedPlan& plan, const std::string& command, const std::string& title);

}  // namespace uwgrasp::experiments
