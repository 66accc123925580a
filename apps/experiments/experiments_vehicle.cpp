// The vehicle in the experiments (not in the thesis, which scores attitude with q_o and leaves
// control as future work, 6.3 and 9.3): what holding an attitude costs the BlueROV2 Heavy's
// thrusters, q_o beside q_v, and whether the thesis presets' top grasps survive the whole-vehicle
// check and can be reached by the simulated vehicle.
#include <filesystem>
#include <numbers>

#include "experiments/experiments.hpp"
#include "experiments/experiments_report.hpp"
#include "app/simulation.hpp"
#include "uwgrasp/grasp/metrics.hpp"
#include "uwgrasp/vehicle/approach.hpp"
#include "uwgrasp/vehicle/thrusters.hpp"
#include "uwgrasp/viz/picture.hpp"

namespace uwgrasp::experiments {

namespace {
constexpr double kPi = std::numbers::pi;

// Utilisation of holding roll (axis 0), pitch (1) or yaw (2) at `angle`.
double hold_at(const vehicle::VehicleParams& p, const vehicle::Allocator& a, int axis, double angle,
               const Eigen::Vector3d& current) {
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  rpy[axis] = angle;
  return vehicle::hold_cost(p, a, rpy, current).utilisation();
}

std::string qo_qv_figure(const io::Config& cfg, const vehicle::Allocator& a, const std::string& dir) {
  const auto& p = cfg.vehicle.params;
  // q_o weighs roll and pitch alike (0.45 each), so one line stands for both.
  std::vector<viz::Series> s = {{"q_o roll, pitch", {}, {}}, {"q_o yaw", {}, {}}, {"q_v roll", {}, {}},
                                {"q_v pitch", {}, {}}, {"q_v yaw", {}, {}}};
  for (int i = 0; i <= 90; ++i) {
    const double angle = -kPi / 4 + kPi / 2 * i / 90.0;
    for (auto& x : s) x.x.push_back(angle * 180 / kPi);
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
      rpy[axis] = angle;
      if (axis != 1) s[axis == 0 ? 0 : 1].y.push_back(grasp::orientation_score(rpy, cfg.grasp.score.orientation));
      s[2 + axis].y.push_back(std::clamp(1.0 - hold_at(p, a, axis, angle, Eigen::Vector3d::Zero()), 0.0, 1.0));
    }
  }
  viz::Axes axes;
  axes.title = "q_o (thesis 6.3) and q_v (thrust), +-45 deg";
  axes.xlabel = "angle deg", axes.ylabel = "score";
  axes.y_lo = 0, axes.y_hi = 1;
  const std::string file = "vehicle_qo_qv.png";
  write_png((std::filesystem::path(dir) / file).string(), viz::line_plot(s, axes));
  return file;
}

// The smallest angle in (0, 90] deg whose hold saturates the thrusters, or a negative value.
double saturation_angle(const vehicle::VehicleParams& p, const vehicle::Allocator& a, int axis,
                        const Eigen::Vector3d& current) {
  for (int d = 1; d <= 90; ++d)
    if (hold_at(p, a, axis, d * kPi / 180, current) > 1.0) return d;
  return -1;
}
}  // namespace

VehicleRun run_vehicle(const grasp::Detection& d, const grasp::Grasp& g, const io::Config& cfg) {
  VehicleRun v;
  const grasp::Gripper gripper = grasp::make_gripper(cfg.grasp.gripper);
  std::vector<Eigen::Vector3f> points;
  grasp::Surroundings around = grasp::surroundings(d.scene, points);
  // The detector's columns under the rest of the scene (its processed points come first).
  if (d.rests.size() >= points.size())
    around.rests = std::span<const char>(d.rests).first(points.size());
  const grasp::Obstacles o = grasp::make_obstacles(around, d.result.frames, cfg.grasp.reach);
  const auto solids = grasp::vehicle_solids(gripper, d.result.frames, cfg.grasp.reach);
  grasp::Candidate c;
  c.position = g.level_from_gripper.translation().cast<float>();
  c.rotation = g.level_from_gripper.linear().cast<float>();
  v.reach = grasp::reach_check(o, solids, c, cfg.grasp.reach);
  v.hold = g.hold_cost;
  vehicle::ApproachTask t = approach_task(g.level_from_vehicle, g.level_from_gripper, cfg);
  t.record_every = 50;  // only the outcome is reported
  for (int k = 0; k < 2; ++k) {
    t.current = k ? Eigen::Vector3d(-kHeadCurrent, 0, 0) : Eigen::Vector3d::Zero();
    const auto r = vehicle::simulate_approach(cfg.vehicle.params, cfg.vehicle.control, t);
    v.reached[k] = r.reached, v.settle[k] = r.settle_time, v.peak[k] = r.peak_utilisation;
  }
  return v;
}

void write_vehicle_model(std::ostringstream& md, const io::Config& cfg, const std::string& dir) {
  const auto& p = cfg.vehicle.params;
  const vehicle::Allocator a = vehicle::make_allocator(p);
  const Eigen::Vector3d head(-kHeadCurrent, 0, 0);
  md << "## The vehicle: what an attitude costs (not in the thesis)\n\n"
        "The thesis scores attitude with q_o = 1 - |sin| per angle (6.3) because restoring forces "
        "pull a tilted vehicle back. uwgrasp prices it: the wrench that holds the attitude against "
        "g(eta) (and a current), allocated to the eight thrusters; utilisation = the largest "
        "thruster's share of its limit (40 N), q_v = 1 - utilisation. BlueROV2 Heavy, "
        "config/vehicle/bluerov2_heavy.yaml (CB 1 cm above CG).\n\n"
        "| angle deg | roll | pitch | yaw | roll, 0.2 m/s head current | pitch, current | yaw, current |\n"
        "|---|---|---|---|---|---|---|\n";
  for (int deg : {0, 15, 30, 45, 60, 75, 90}) {
    md << "| " << deg;
    for (const Eigen::Vector3d& cur : {Eigen::Vector3d::Zero().eval(), head})
      for (int axis = 0; axis < 3; ++axis) md << " | " << fmt("%.1f %%", 100 * hold_at(p, a, axis, deg * kPi / 180, cur));
    md << " |\n";
  }
  md << "\nSaturation angle (utilisation > 100 %):";
  const char* names[3] = {"roll", "pitch", "yaw"};
  for (int axis = 0; axis < 3; ++axis) {
    const double s = saturation_angle(p, a, axis, Eigen::Vector3d::Zero());
    md << " " << names[axis] << " " << (s > 0 ? fmt("%.0f deg", s) : std::string("none up to 90 deg")) << (axis < 2 ? ";" : ".");
  }
  md << "\n\n![q_o and q_v](" << qo_qv_figure(cfg, a, dir) << ")\n\n";
}

void write_vehicle_runs(std::ostringstream& md, const ConditionResult& r) {
  md << "### The vehicle on the top grasps\n\n"
        "Each iteration's best grasp (Table 8.5 presets, found without the whole-vehicle check as "
        "in the thesis) checked with the hull and the straight approach from the standoff against "
        "the whole processed scene and the seafloor plane, and driven onto by the simulated "
        "vehicle from where it took the picture: in still water and in a 0.2 m/s current from "
        "ahead.\n\n"
        "| object | top grasps | whole vehicle fits | rejected as | hold cost | reached, still | "
        "reached, 0.2 m/s | settle s, still | settle s, current | peak thrust use, current |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& f : r.finals) {
    std::size_t fits = 0, reached[2] = {0, 0};
    grasp::RejectCounts why{};
    std::vector<double> hold, settle[2], peak;
    for (const VehicleRun& v : f.vehicle) {
      fits += v.reach == grasp::Reject::none;
      ++why[static_cast<std::size_t>(v.reach)];
      hold.push_back(100 * v.hold);
      peak.push_back(100 * v.peak[1]);
      for (int k = 0; k < 2; ++k) {
        reached[k] += v.reached[k];
        if (v.settle[k] >= 0) settle[k].push_back(v.settle[k]);
      }
    }
    std::string reasons;
    for (int k = 1; k < grasp::kRejectKinds; ++k)
      if (why[static_cast<std::size_t>(k)])
        reasons += (reasons.empty() ? "" : ", ") + std::string(grasp::reject_name(static_cast<grasp::Reject>(k))) +
                   " " + std::to_string(why[static_cast<std::size_t>(k)]);
    const std::size_t n = f.vehicle.size();
    md << "| " << f.name << " | " << n << " | " << fits << " | " << (reasons.empty() ? "-" : reasons) << " | "
       << median_range(hold, " %", "%.1f") << " | " << reached[0] << "/" << n << " | " << reached[1] << "/" << n
       << " | " << median_range(settle[0], "", "%.1f") << " | " << median_range(settle[1], "", "%.1f") << " | "
       << median_range(peak, " %", "%.0f") << " |\n";
  }
  md << "\n";
}

}  // namespace uwgrasp::experiments
