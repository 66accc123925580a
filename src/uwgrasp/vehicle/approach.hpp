#pragma once
// Approach simulation (thesis 9.3, future work): the vehicle drives from where it is to a
// standoff pose in front of the grasp, then straight along the gripper's approach axis onto the
// grasp pose and holds it - the model, the thrusters with their limits, the controller and an
// optional constant current, integrated with RK4.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "uwgrasp/vehicle/control.hpp"
#include "uwgrasp/vehicle/model.hpp"

namespace uwgrasp::vehicle {

enum class Phase { transit, approach, hold };
const char* phase_name(Phase p);

struct Sample {
  double t = 0;
  Phase phase = Phase::transit;
  State state;
  Reference reference;
  Vector6d error = Vector6d::Zero();  // against the reference (pose_error)
  Eigen::VectorXd thrust;             // N per thruster
  double utilisation = 0;             // of the commanded wrench (> 1: saturated and scaled)
  double goal_position_error = 0, goal_attitude_error = 0;  // against the grasp pose
  double path_deviation = 0;  // distance from the straight standoff-to-grasp line (approach, hold)
};

struct ApproachResult {
  std::vector<Sample> trajectory;  // every `record_every` steps, and the last
  bool reached = false;            // within tolerance of the grasp for hold_time, by max_time
  double standoff_time = 0;        // when the reference reached the standoff, s
  double arrival_time = 0;         // when the reference reached the grasp pose, s
  double settle_time = -1;         // from the start until within tolerance for good; -1: never
  double final_position_error = 0, final_attitude_error = 0;
  double peak_utilisation = 0;     // over the whole run (> 1: the thrusters saturated)
  double max_path_deviation = 0;   // during the straight approach, m
};

struct ApproachTask {
  State start;                 // where the vehicle is (position in N = L, at rest)
  Eigen::Vector3d goal = Eigen::Vector3d::Zero();  // T_LB of the grasp
  Eigen::Quaterniond goal_attitude = Eigen::Quaterniond::Identity();
  Eigen::Vector3d approach_axis = Eigen::Vector3d::UnitX();  // the gripper's x in L
  double standoff = 0.3;       // m back along the approach axis; 0: straight onto the grasp
  Eigen::Vector3d current = Eigen::Vector3d::Zero();  // in N, m/s
  int record_every = 5;        // steps between trajectory samples
};

// Throws Error for invalid parameters or control settings, a non-unit approach axis or a
// negative standoff. The same task always gives the same trajectory.
ApproachResult simulate_approach(const VehicleParams& p, const ControlConfig& c,
                                 const ApproachTask& task);
// The controller and allocator use `model`, the simulated vehicle is `plant`: how the approach
// fares when the configured parameters are wrong (same thruster layout).
ApproachResult simulate_approach(const VehicleParams& model, const VehicleParams& plant,
                                 const ControlConfig& c, const ApproachTask& task);

}  // namespace uwgrasp::vehicle
