#pragma once
// uwgrasp experiments: the thesis's chapter 8 repeated on the simulated scenes, once per water
// condition - tables 8.1-8.5 and figures 8.13-8.16 - with what each measurement found.
#include <cstdint>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "uwgrasp/eval/summary.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"

namespace uwgrasp::experiments {

// The studies are the CLI's: they share its sessions, simulations and output helpers.
using namespace uwgrasp::app;

struct Condition {
  std::string name;   // as the report and file names name it
  std::string water;  // sim water preset
  bool noise = false; // depth noise, dropouts and marine snow
  std::vector<std::string> sets;  // settings on top of every preset (empty: the thesis's)
};
// The settings that suit a realistic sensor in `water`: colour restoration with the water's
// coefficients, wider normals, and region growing that tolerates the noise.
std::vector<std::string> adapted_settings(const std::string& water);

struct ExperimentPlan {
  io::Config base;                 // the session's config (seed, threads, sim.camera)
  std::vector<std::string> sets;   // --set overrides, applied on top of every preset
  int iterations = 50;             // tables 8.3, 8.5 and figures 8.13-8.16 (the thesis: 50)
  int short_iterations = 10;       // tables 8.1, 8.2, 8.4 (the thesis: 10)
  int brute_iterations = 3;        // the thesis's all-points collision check (slow) in table 8.4
};

// Mean, median and range of repeated measurements.
struct Summary {
  double mean = 0, median = 0, min = 0, max = 0;
  std::size_t n = 0;
};
Summary summarise(std::vector<double> values);

// Tables 8.1 / 8.2: preprocessing and segmentation of the barbell scene's whole frame.
struct SegmentRun {
  double finite_ms = 0, plane_ms = 0, normals_ms = 0, region_ms = 0;
  std::size_t points = 0, segments = 0;
  double iou = 0;  // the segment that best matches the barbell's true pixels: |S n T| / |S u T|
  double object_iou = 0;  // the segments the barbell preset selects as the object
};
struct SegmentStudy {
  std::vector<SegmentRun> without_plane, with_plane;
};

// Table 8.3: one object, one sampler, 5000 candidates per iteration.
// The top grasps of one detection judged against the true shapes (eval/): not in the thesis,
// which judged its final grasps by inspection (8.5).
struct Judged {
  eval::Summary summary;
  std::string top1;  // the top-1's outcome at the reference mu ("no grasp" when there is none)
};

struct SamplerRow {
  std::string object;
  grasp::SamplerKind kind = grasp::SamplerKind::normal;
  std::uint32_t samples = 5000;
  std::vector<double> sample_ms, collision_free, feasible;
  std::vector<Judged> judged;  // per iteration, its top 10
};

// Table 8.4: 3000 candidates checked on the barbell's full and voxelised object cloud.
struct CheckRun {
  std::size_t full_points = 0, voxel_points = 0, feasible_full = 0, feasible_voxel = 0;
  double check_full_ms = 0, voxel_ms = 0, check_voxel_ms = 0;
  double brute_full_ms = -1, brute_voxel_ms = -1;  // -1: not run this iteration
  bool agree = true;  // the all-points check rejected exactly the same candidates
};
struct CheckStudy {
  double hfov = 0;  // rad: the narrower view that gives the barbell the thesis's point count
  std::vector<CheckRun> runs;
};

// The vehicle on a top grasp (not in the thesis; its 9.3 future work): the whole-vehicle check
// against the scene, the hold cost, and the approach in still water and in a head current.
struct VehicleRun {
  grasp::Reject reach = grasp::Reject::none;
  double hold = 0;                 // thruster utilisation of holding the attitude
  bool reached[2] = {false, false};  // still water, head current
  double settle[2] = {-1, -1}, peak[2] = {0, 0};
};
inline constexpr double kHeadCurrent = 0.2;  // m/s, flowing from ahead (-x in L)

// Figures 8.13-8.16: the best grasp of each iteration on one object, with its preset.
struct FinalObject {
  std::string name;
  io::Config cfg;
  grasp::Frames frames;
  std::vector<grasp::Grasp> best;  // one per iteration that found a feasible grasp
  std::vector<double> feasible, detect_ms;
  std::vector<double> coverage;    // object points / the object's visible pixels (truth labels)
  std::vector<VehicleRun> vehicle; // per best grasp
  std::size_t failures = 0;        // iterations where detection stopped with an error
  std::vector<std::string> errors; // their distinct messages
  std::vector<Judged> judged;      // per iteration (failures included), the preset's top 10
  Cloud view;                      // the first iteration's frame, for the figure
  std::vector<Eigen::Vector3f> focus;
};

struct ConditionResult {
  Condition condition;
  SegmentStudy segmentation;
  std::vector<SamplerRow> sampling;
  CheckStudy checking;
  std::vector<FinalObject> finals;
  double seconds = 0;
};

// One progress line on stderr: "uwgrasp experiments [coastal] table 8.4: iteration 3/10".
void experiment_step(const Condition& c, const char* what, int i, int n);

// The studies; each iteration i renders with seed + i and prints its progress.
SegmentStudy run_segmentation_study(const ExperimentPlan& plan, const Condition& c);
CheckStudy run_check_study(const ExperimentPlan& plan, const Condition& c);
// Tables 8.3 and 8.5, figures 8.13-8.16 (they share the rendered frames).
void run_sampling_study(const ExperimentPlan& plan, const Condition& c, ConditionResult& out);

// The vehicle on a detection's top grasp (thesis presets run without the whole-vehicle check).
VehicleRun run_vehicle(const grasp::Detection& d, const grasp::Grasp& g, const io::Config& cfg);

// Every condition of the thesis study - each water in `waters`, and for coastal and turbid also
// with the adapted settings - with tables 8.1-8.5 and figures 8.13-8.16 each.
std::vector<ConditionResult> run_thesis_study(const ExperimentPlan& plan,
                                              const std::vector<std::string>& waters);

// The detection's top grasps (at most summary.top) judged in `world`, seen by the frame's camera.
Judged judge_detection(const sim::World& world, const sim::Frame& f, const grasp::Detection& d,
                       int target, const grasp::GripperConfig& gripper, std::uint64_t seed);

// DIR/report.md and its PNGs; `command` is the command line that made them.
void write_report(const std::string& dir, const std::vector<ConditionResult>& results,
                  const ExperimentPlan& plan, const std::string& command);

}  // namespace uwgrasp::experiments
