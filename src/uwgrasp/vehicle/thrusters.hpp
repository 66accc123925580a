#pragma once
// Thrust allocation (Fossen 2011, 11.2): tau = K f with K's column i = [d_i; r_i x d_i] for a
// thruster at r_i thrusting along d_i, and the hold cost of an attitude (thesis 6.3 motivates
// q_o with restoring forces; this is what they actually cost the thrusters).
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "uwgrasp/vehicle/model.hpp"

namespace uwgrasp::vehicle {

using AllocationMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic>;

AllocationMatrix allocation_matrix(const std::vector<Thruster>& thrusters);

// A prepared allocator: the minimum-norm solution f = K^+ tau (K^+ = K^T (K K^T)^-1), bounded
// per thruster to [f_min, f_max]. Throws Error when K has rank < 6 (some wrench direction
// cannot be produced) or the limits do not straddle 0.
struct Allocator {
  AllocationMatrix K;
  Eigen::Matrix<double, Eigen::Dynamic, 6> K_pinv;
  double f_min = -40, f_max = 40;
};
Allocator make_allocator(const VehicleParams& p);

struct Allocation {
  Eigen::VectorXd thrust;  // N per thruster, within the limits
  Vector6d achieved = Vector6d::Zero();  // K * thrust
  Vector6d residual = Vector6d::Zero();  // requested - achieved: zero unless saturated
  // Largest share of its limit any thruster needs for the requested wrench (f_i / f_max for
  // forward thrust, f_i / f_min for reverse): > 1 means the wrench is beyond the thrusters, and
  // then every thrust is scaled by 1 / utilisation - the same wrench direction, as much of it as
  // the thrusters give. Minimum norm is not minimum peak: a wrench slightly past 1 here may be
  // reachable through K's null space, so this is conservative.
  double utilisation = 0;
  bool saturated() const { return utilisation > 1.0; }
};
Allocation allocate(const Allocator& a, const Vector6d& tau);

// The static wrench that holds the vehicle still at roll, pitch (and yaw, which matters only
// with a current) against g(eta), and the drag of a constant current in N if one is given:
// tau = g(eta) + C_A(nu_r) nu_r + D(nu_r) nu_r with nu = 0, nu_r = -nu_c.
Vector6d hold_wrench(const VehicleParams& p, const Eigen::Vector3d& rpy,
                     const Eigen::Vector3d& current = Eigen::Vector3d::Zero());

struct HoldCost {
  Vector6d wrench = Vector6d::Zero();
  Allocation allocation;
  double utilisation() const { return allocation.utilisation; }
  bool feasible() const { return !allocation.saturated(); }
  // q_v = 1 - utilisation, clamped to [0, 1]: the vehicle score beside the thesis's q_o.
  double score() const;
};
HoldCost hold_cost(const VehicleParams& p, const Allocator& a, const Eigen::Vector3d& rpy,
                   const Eigen::Vector3d& current = Eigen::Vector3d::Zero());

// The utilisation of holding an attitude (roll, pitch, yaw) in a constant current, as a
// thread-safe function - what grasp::ScoreConfig::hold_cost expects. Throws Error as
// make_allocator does.
std::function<double(const Eigen::Vector3d& rpy)> hold_cost_function(
    const VehicleParams& p, const Eigen::Vector3d& current = Eigen::Vector3d::Zero());

}  // namespace uwgrasp::vehicle
