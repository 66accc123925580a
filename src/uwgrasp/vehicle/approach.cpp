#include "uwgrasp/vehicle/approach.hpp"

#include <algorithm>
#include <cmath>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/vehicle/thrusters.hpp"

namespace uwgrasp::vehicle {

namespace {
struct Plan {
  Segment transit, approach;
  double arrival() const { return transit.duration + approach.duration; }
};

Plan plan(const ControlConfig& c, const ApproachTask& task) {
  const Eigen::Vector3d standoff = task.goal - task.standoff * task.approach_axis;
  return {make_segment(task.start.position, task.start.attitude, standoff, task.goal_attitude,
                       c.transit_speed, c.turn_rate),
          make_segment(standoff, task.goal_attitude, task.goal, task.goal_attitude,
                       c.approach_speed, c.turn_rate)};
}

Phase reference(const Plan& p, double t, Reference& r) {
  if (t < p.transit.duration) {
    r = reference_at(p.transit, t);
    return Phase::transit;
  }
  if (t < p.arrival()) {
    r = reference_at(p.approach, t - p.transit.duration);
    return Phase::approach;
  }
  r = reference_at(p.approach, p.approach.duration);
  return Phase::hold;
}

// Distance from the straight standoff-to-grasp segment.
double deviation(const ApproachTask& task, const Eigen::Vector3d& x) {
  const Eigen::Vector3d from = task.goal - task.standoff * task.approach_axis;
  const double along = std::clamp((x - from).dot(task.approach_axis), 0.0, task.standoff);
  return (x - from - along * task.approach_axis).norm();
}

void check_task(const ApproachTask& t) {
  if (!t.goal.allFinite() || !t.start.position.allFinite() || !t.current.allFinite())
    throw Error("approach: start, goal and current must be finite");
  if (std::abs(t.approach_axis.norm() - 1.0) > 1e-6)
    throw Error("approach: the approach axis must be a unit vector");
  if (!(t.standoff >= 0.0)) throw Error("approach: the standoff must be >= 0");
  if (t.record_every < 1) throw Error("approach: record_every must be >= 1");
}
}  // namespace

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::transit: return "transit";
    case Phase::approach: return "approach";
    default: return "hold";
  }
}

ApproachResult simulate_approach(const VehicleParams& p, const ControlConfig& c,
                                 const ApproachTask& task) {
  return simulate_approach(p, p, c, task);
}

ApproachResult simulate_approach(const VehicleParams& p, const VehicleParams& plant,
                                 const ControlConfig& c, const ApproachTask& task) {
  check_params(p);
  check_params(plant);
  check_task(task);
  const Allocator alloc = make_allocator(p);
  Controller k = make_controller(p, c);
  const Plan path = plan(c, task);
  ApproachResult out;
  out.standoff_time = path.transit.duration;
  out.arrival_time = path.arrival();
  State s = task.start;
  bool saturated = false;
  double inside_since = -1.0;
  const auto steps = static_cast<long>(std::ceil(c.max_time / c.dt));
  for (long i = 0; i <= steps; ++i) {
    Sample x;
    x.t = static_cast<double>(i) * c.dt;
    x.phase = reference(path, x.t, x.reference);
    x.state = s;
    x.error = pose_error(s, x.reference.position, x.reference.attitude);
    const Allocation a = allocate(alloc, control(k, p, s, x.reference, c.dt, saturated));
    saturated = a.saturated();
    x.thrust = a.thrust, x.utilisation = a.utilisation;
    const Vector6d goal = pose_error(s, task.goal, task.goal_attitude);
    x.goal_position_error = goal.head<3>().norm(), x.goal_attitude_error = goal.tail<3>().norm();
    if (x.phase != Phase::transit) x.path_deviation = deviation(task, s.position);
    out.peak_utilisation = std::max(out.peak_utilisation, a.utilisation);
    out.max_path_deviation = std::max(out.max_path_deviation, x.path_deviation);
    const bool within = x.goal_position_error <= c.position_tolerance &&
                        x.goal_attitude_error <= c.attitude_tolerance;
    inside_since = within ? (inside_since < 0 ? x.t : inside_since) : -1.0;
    out.reached = x.phase == Phase::hold && inside_since >= 0 &&
                  x.t - std::max(inside_since, out.arrival_time) >= c.hold_time - 1e-9;
    const bool last = out.reached || i == steps;
    if (i % task.record_every == 0 || last) out.trajectory.push_back(x);
    if (last) {
      out.final_position_error = x.goal_position_error;
      out.final_attitude_error = x.goal_attitude_error;
      break;
    }
    s = rk4_step(plant, s, a.achieved, task.current, c.dt);
  }
  if (out.reached) out.settle_time = inside_since;
  return out;
}

}  // namespace uwgrasp::vehicle
