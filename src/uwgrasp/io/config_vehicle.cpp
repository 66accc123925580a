// The vehicle section of the config schema (rigid body, hydrodynamics, thrusters, current,
// controller). Six-vectors are written per degree of freedom, thrusters as t1 ... t8.
#include "uwgrasp/io/config_schema.hpp"

namespace uwgrasp::io {

namespace {
constexpr double kTiny = 1e-9;

void visit_dofs(Visitor& v, const char* name, vehicle::Vector6d& x, double lo, double hi) {
  static const char* dof[6] = {"surge", "sway", "heave", "roll", "pitch", "yaw"};
  v.section(name, [&] {
    for (int i = 0; i < 6; ++i) v.field(dof[i], x[i], lo, hi);
  });
}

void visit_control(Visitor& v, vehicle::ControlConfig& c) {
  v.field("position_bandwidth", c.position_bandwidth, kTiny, 100.0);
  v.field("attitude_bandwidth", c.attitude_bandwidth, kTiny, 100.0);
  v.field("transit_speed", c.transit_speed, kTiny, 10.0);
  v.field("approach_speed", c.approach_speed, kTiny, 10.0);
  v.field("turn_rate", c.turn_rate, kTiny, 10.0);
  v.field("dt", c.dt, 1e-5, 1.0);
  v.field("max_time", c.max_time, kTiny, 1e5);
  v.field("position_tolerance", c.position_tolerance, kTiny, 10.0);
  v.field("attitude_tolerance", c.attitude_tolerance, kTiny, 3.2);
  v.field("hold_time", c.hold_time, kTiny, 1e4);
}
}  // namespace

void visit_vehicle(Visitor& v, VehicleConfig& c) {
  vehicle::VehicleParams& p = c.params;
  if (p.thrusters.size() != 8) p.thrusters = vehicle::heavy_thrusters();
  v.field("mass", p.mass, kTiny, 1e6);
  v.field("volume", p.volume, kTiny, 1e3);
  v.field("rho", p.rho, kTiny, 1e4);
  v.field("gravity", p.gravity, kTiny, 100.0);
  v.field("inertia", p.inertia, kTiny, 1e6);
  v.field("r_g", p.r_g, -10.0, 10.0);
  v.field("r_b", p.r_b, -10.0, 10.0);
  visit_dofs(v, "added_mass", p.added_mass, 0.0, 1e6);
  visit_dofs(v, "linear_damping", p.linear_damping, 0.0, 1e6);
  visit_dofs(v, "quadratic_damping", p.quadratic_damping, 0.0, 1e6);
  v.section("thrust", [&] {
    v.field("min", p.thrust_min, -1e6, -kTiny);
    v.field("max", p.thrust_max, kTiny, 1e6);
  });
  v.section("thrusters", [&] {
    static const char* names[8] = {"t1", "t2", "t3", "t4", "t5", "t6", "t7", "t8"};
    for (std::size_t i = 0; i < 8; ++i)
      v.section(names[i], [&] {
        v.field("position", p.thrusters[i].position, -10.0, 10.0);
        v.field("direction", p.thrusters[i].direction, -1.0, 1.0);
      });
  });
  v.field("current", c.current, -10.0, 10.0);
  v.section("control", [&] { visit_control(v, c.control); });
}

}  // namespace uwgrasp::io
