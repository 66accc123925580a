#include "uwgrasp/vehicle/thrusters.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <memory>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/pose.hpp"

namespace uwgrasp::vehicle {

AllocationMatrix allocation_matrix(const std::vector<Thruster>& thrusters) {
  AllocationMatrix K(6, static_cast<Eigen::Index>(thrusters.size()));
  for (std::size_t i = 0; i < thrusters.size(); ++i) {
    const Eigen::Vector3d d = thrusters[i].direction.normalized();
    K.col(static_cast<Eigen::Index>(i)) << d, thrusters[i].position.cross(d);
  }
  return K;
}

Allocator make_allocator(const VehicleParams& p) {
  check_params(p);
  Allocator a;
  a.K = allocation_matrix(thrusters_of(p));
  a.f_min = p.thrust_min;
  a.f_max = p.thrust_max;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a.K);
  const auto& s = svd.singularValues();
  const Eigen::Index rank = (s.array() > 1e-9 * std::max(1.0, s(0))).count();
  if (rank < 6)
    throw Error("vehicle.thrusters: the allocation matrix has rank " + std::to_string(rank) +
                " < 6, so some force or moment cannot be produced (check positions and directions)");
  const Matrix6d KKt = a.K * a.K.transpose();
  a.K_pinv = a.K.transpose() * KKt.inverse();
  return a;
}

namespace {
// The largest share of its limit any thruster needs for `thrust` (Allocation::utilisation).
double utilisation_of(const Allocator& a, const Eigen::VectorXd& thrust) {
  double u = 0;
  for (Eigen::Index i = 0; i < thrust.size(); ++i) {
    const double f = thrust(i);
    u = std::max(u, f >= 0 ? f / a.f_max : f / a.f_min);
  }
  return u;
}
}  // namespace

Allocation allocate(const Allocator& a, const Vector6d& tau) {
  Allocation out;
  out.thrust.noalias() = a.K_pinv * tau;
  out.utilisation = utilisation_of(a, out.thrust);
  if (out.saturated()) out.thrust /= out.utilisation;
  out.achieved = a.K * out.thrust;
  out.residual = tau - out.achieved;
  return out;
}

Vector6d hold_wrench(const VehicleParams& p, const Eigen::Vector3d& rpy, const Eigen::Vector3d& current) {
  const Eigen::Quaterniond q = quat_from_rpy(rpy);
  Vector6d nu_r = Vector6d::Zero();
  nu_r.head<3>() = -(q.conjugate() * current);
  return restoring(p, q) + coriolis(added_mass(p), nu_r) * nu_r + damping(p, nu_r) * nu_r;
}

double HoldCost::score() const { return std::clamp(1.0 - allocation.utilisation, 0.0, 1.0); }

HoldCost hold_cost(const VehicleParams& p, const Allocator& a, const Eigen::Vector3d& rpy,
                   const Eigen::Vector3d& current) {
  HoldCost h;
  h.wrench = hold_wrench(p, rpy, current);
  h.allocation = allocate(a, h.wrench);
  return h;
}

std::function<double(const Eigen::Vector3d& rpy)> hold_cost_function(
    const VehicleParams& p, const Eigen::Vector3d& current) {
  if (!current.allFinite()) throw Error("vehicle.current must be finite");
  auto a = std::make_shared<const Allocator>(make_allocator(p));
  return [p, a, current](const Eigen::Vector3d& rpy) {
    // Scoring calls this for every feasible candidate, on the worker threads: each keeps its
    // thrust vector, so a stream of frames does not ask the allocator for one a call (it did
    // ~1,000 times a frame). The same product and bound as allocate(), so the same utilisation.
    thread_local Eigen::VectorXd thrust;
    thrust.noalias() = a->K_pinv * hold_wrench(p, rpy, current);
    return utilisation_of(*a, thrust);
  };
}

}  // namespace uwgrasp::vehicle
