// uwgrasp approach --grasps GRASPS.json: the vehicle driving onto one of the grasps (thesis 9.3,
// future work) - from where it was at capture to the standoff, then straight onto the grasp -
// with its controller, thrusters and an optional current. Prints the outcome, optionally writes
// the trajectory (CSV) and a PNG of errors and thruster use over time.
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <sstream>

#include "app/common.hpp"
#include "commands.hpp"
#include "app/simulation.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/atomic_file.hpp"
#include "uwgrasp/io/grasps_json.hpp"
#include "uwgrasp/vehicle/approach.hpp"
#include "uwgrasp/viz/picture.hpp"

namespace uwgrasp::app {

namespace {
struct ApproachOptions {
  CommonOptions common;
  std::string grasps, object, current, out;
  std::int64_t rank = 1;
};

constexpr double kDeg = 180.0 / std::numbers::pi;

Eigen::Vector3d parse_current(const std::string& s) {
  std::stringstream in(s);
  Eigen::Vector3d v;
  char c1 = 0, c2 = 0;
  if (!(in >> v.x() >> c1 >> v.y() >> c2 >> v.z()) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof() ||
      !v.allFinite() || v.norm() > 10.0)
    throw Error("--current '" + s + "': expected X,Y,Z in m/s (level frame, |v| <= 10)");
  return v;
}

std::string csv(const vehicle::ApproachResult& r) {
  std::ostringstream o;
  o << "t,phase,x,y,z,roll,pitch,yaw,ref_x,ref_y,ref_z,position_error,attitude_error,"
       "path_deviation,utilisation";
  const std::size_t n = r.trajectory.empty() ? 0 : std::size_t(r.trajectory.front().thrust.size());
  for (std::size_t i = 0; i < n; ++i) o << ",f" << i + 1;
  o << "\n";
  char line[96];
  for (const auto& s : r.trajectory) {
    const Eigen::Vector3d rpy = rpy_from_quat(s.state.attitude);
    std::snprintf(line, sizeof line, "%.3f,%s", s.t, vehicle::phase_name(s.phase));
    o << line;
    for (double v : {s.state.position.x(), s.state.position.y(), s.state.position.z(), rpy.x(), rpy.y(),
                     rpy.z(), s.reference.position.x(), s.reference.position.y(), s.reference.position.z(),
                     s.goal_position_error, s.goal_attitude_error, s.path_deviation, s.utilisation}) {
      std::snprintf(line, sizeof line, ",%.6g", v);
      o << line;
    }
    for (Eigen::Index i = 0; i < s.thrust.size(); ++i) {
      std::snprintf(line, sizeof line, ",%.4f", s.thrust[i]);
      o << line;
    }
    o << "\n";
  }
  return o.str();
}

cv::Mat plots(const vehicle::ApproachResult& r, const io::VehicleConfig& v, const std::string& title) {
  std::vector<double> t;
  viz::Series pos{"to grasp", {}, {}}, track{"to reference", {}, {}}, att{"to grasp", {}, {}},
      util{"utilisation", {}, {}};
  const std::size_t n = r.trajectory.empty() ? 0 : std::size_t(r.trajectory.front().thrust.size());
  std::vector<viz::Series> thrust(n);
  for (std::size_t i = 0; i < n; ++i) thrust[i].name = "T" + std::to_string(i + 1);
  for (const auto& s : r.trajectory) {
    t.push_back(s.t);
    pos.y.push_back(s.goal_position_error);
    track.y.push_back(s.error.head<3>().norm());
    att.y.push_back(s.goal_attitude_error * kDeg);
    util.y.push_back(s.utilisation);
    for (std::size_t i = 0; i < n; ++i) thrust[i].y.push_back(s.thrust[Eigen::Index(i)]);
  }
  for (viz::Series* s : {&pos, &track, &att, &util}) s->x = t;
  for (auto& s : thrust) s.x = t;
  const auto& c = v.control;
  // Dashed: tolerances and limits; vertical: standoff reached (reference), grasp reached.
  const std::vector<double> events = {r.standoff_time, r.arrival_time};
  viz::Axes a1{title + ": position error", "t s", "m", 0, 0, {c.position_tolerance}, events};
  viz::Axes a2{"attitude error", "t s", "deg", 0, 0, {c.attitude_tolerance * kDeg}, events};
  viz::Axes a3{"thrust per thruster", "t s", "N", 0, 0, {v.params.thrust_min, v.params.thrust_max}, events};
  viz::Axes a4{"thruster utilisation (1 = a thruster at its limit)", "t s", "", 0, 0, {1.0}, events};
  const viz::Series p2[] = {pos, track};
  const cv::Mat tiles[] = {viz::line_plot(p2, a1), viz::line_plot(std::span(&att, 1), a2),
                           viz::line_plot(thrust, a3), viz::line_plot(std::span(&util, 1), a4)};
  return viz::grid(tiles, 2);
}

void print_result(const vehicle::ApproachResult& r, const io::GraspRecord& g, const Eigen::Vector3d& current) {
  const Eigen::Vector3d p = g.level_from_vehicle.translation();
  const Eigen::Vector3d rpy = rpy_from_matrix(g.level_from_vehicle.linear()) * kDeg;
  std::printf("grasp %zu%s%s (score %.3f): vehicle to (%.3f, %.3f, %.3f) m, rpy (%.1f, %.1f, %.1f) deg\n",
              g.rank, g.object.empty() ? "" : " on the ", g.object.c_str(), g.score, p.x(), p.y(), p.z(),
              rpy.x(), rpy.y(), rpy.z());
  std::printf("current (%.2f, %.2f, %.2f) m/s; standoff %.2f m\n", current.x(), current.y(), current.z(),
              g.config.grasp.reach.standoff);
  std::printf("reached: %s\n", r.reached ? "yes" : "NO");
  if (r.settle_time >= 0)
    std::printf("settled at %.1f s: within %.0f mm and %.1f deg from then on (the reference arrived at %.1f s)\n",
                r.settle_time, 1000 * g.config.vehicle.control.position_tolerance,
                g.config.vehicle.control.attitude_tolerance * kDeg, r.arrival_time);
  else
    std::printf("not settled within %.0f s (the reference arrived at %.1f s)\n",
                g.config.vehicle.control.max_time, r.arrival_time);
  std::printf("final error %.1f mm, %.2f deg; largest distance from the approach line %.1f mm\n",
              1000 * r.final_position_error, r.final_attitude_error * kDeg, 1000 * r.max_path_deviation);
  std::printf("peak thruster utilisation %.0f %%%s\n", 100 * r.peak_utilisation,
              r.peak_utilisation > 1 ? " (saturated)" : "");
}
}  // namespace

void add_approach_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners) {
  auto* cmd = app.add_subcommand("approach", "Simulate the vehicle driving onto a grasp from grasps.json");
  auto o = std::make_shared<ApproachOptions>();
  cmd->add_option("--grasps", o->grasps, "grasps.json from detect or demo")->required();
  cmd->add_option("--rank", o->rank, "Which grasp (1 = best)")->check(CLI::Range(1, 1000000));
  cmd->add_option("--object", o->object, "Object name in a demo file (default: the first)");
  cmd->add_option("--current", o->current, "Constant current X,Y,Z in m/s, level frame (default: vehicle.current)");
  cmd->add_option("--out", o->out, "Write approach.csv and approach.png here");
  add_common(*cmd, o->common);
  runners.emplace_back(cmd, [o] {
    const Session session = open_session(o->common);  // seed and threads; --set checked here too
    io::GraspRecord g = io::read_grasp(o->grasps, std::size_t(o->rank), o->object, o->common.sets);
    if (!o->common.config_path.empty()) g.config = session.config;
    const io::VehicleConfig& v = g.config.vehicle;
    const Eigen::Vector3d current = o->current.empty() ? v.current : parse_current(o->current);
    vehicle::ApproachTask task = approach_task(g.level_from_vehicle, g.level_from_gripper, g.config);
    task.current = current;
    progress("uwgrasp approach: simulating");
    const vehicle::ApproachResult r = vehicle::simulate_approach(v.params, v.control, task);
    print_result(r, g, current);
    if (!o->out.empty()) {
      make_output_dir(o->out);
      const auto path = [&](const char* f) { return (std::filesystem::path(o->out) / f).string(); };
      const std::string table = csv(r);  // both made before either is written
      const cv::Mat picture = plots(r, v, "grasp " + std::to_string(g.rank));
      io::write_text(path("approach.csv"), table);
      write_png(path("approach.png"), picture);
      std::printf("wrote %s: approach.csv approach.png\n", o->out.c_str());
    }
    return 0;
  });
}

}  // namespace uwgrasp::app
