#pragma once
// Pose control of the vehicle (the thesis's future work, Figure 1.1's red node; Fossen 2011,
// 12.2-12.3): a body-frame PID per degree of freedom with feedforward of the reference's
// acceleration and drag and compensation of the restoring forces g(eta), and a reference model
// that moves the setpoint along straight lines with minimum-jerk timing.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "uwgrasp/vehicle/model.hpp"
#include "uwgrasp/vehicle/thrusters.hpp"

namespace uwgrasp::vehicle {

struct ControlConfig {
  // Closed-loop bandwidths: all three poles of each PID loop at -bandwidth (Kp = 3 m w^2,
  // Kd = 3 m w, Ki = m w^3 with m the diagonal of M), so the loops do not ring.
  double position_bandwidth = 1.0;  // rad/s, surge/sway/heave
  double attitude_bandwidth = 3.0;  // rad/s, roll/pitch/yaw
  double transit_speed = 0.2;       // m/s, peak reference speed to the standoff
  double approach_speed = 0.05;     // m/s, peak reference speed from the standoff onto the grasp
  double turn_rate = 0.3;           // rad/s, peak reference turn rate
  double dt = 0.01;                 // s, integration and control step
  double max_time = 180.0;          // s, simulated time limit
  double position_tolerance = 0.02; // m: the grasp is reached within this ...
  double attitude_tolerance = 0.035;  // rad (2 degrees) ... and this ...
  double hold_time = 3.0;           // s ... held this long
};
// Throws Error naming the field for a non-positive or non-finite value.
void check_control(const ControlConfig& c);

// Where the setpoint is: pose, and velocity and acceleration in N (angular ones in B).
struct Reference {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), acceleration = Eigen::Vector3d::Zero();
  Eigen::Vector3d omega = Eigen::Vector3d::Zero(), alpha = Eigen::Vector3d::Zero();
};

// A straight move from one pose to another: position along the line, attitude by slerp, both
// on the minimum-jerk profile s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5, whose peak rate is 1.875
// times the mean; the duration makes the peak speed and turn rate the given limits.
struct Segment {
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_from = Eigen::Quaterniond::Identity(), q_to = Eigen::Quaterniond::Identity();
  double duration = 0.0;
};
Segment make_segment(const Eigen::Vector3d& from, const Eigen::Quaterniond& q_from,
                     const Eigen::Vector3d& to, const Eigen::Quaterniond& q_to, double speed,
                     double turn_rate);
Reference reference_at(const Segment& s, double t);

// Position error (in B) and attitude error (rotation vector in B) of a state against a pose.
Vector6d pose_error(const State& s, const Eigen::Vector3d& position, const Eigen::Quaterniond& q);

struct Controller {
  Matrix6d M = Matrix6d::Zero();
  Vector6d kp = Vector6d::Zero(), kd = Vector6d::Zero(), ki = Vector6d::Zero();
  Vector6d integral = Vector6d::Zero();
};
Controller make_controller(const VehicleParams& p, const ControlConfig& c);
// The wrench for this step, before allocation. The integral advances by dt unless the previous
// step saturated (conditional integration, so it does not wind up while thrust is short).
Vector6d control(Controller& k, const VehicleParams& p, const State& s, const Reference& r,
                 double dt, bool saturated);

}  // namespace uwgrasp::vehicle
