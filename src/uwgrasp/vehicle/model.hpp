#pragma once
// Fossen's 6-DoF vehicle model (thesis ch. 2, eq. 2.7-2.22; Fossen 2011 ch. 3-4):
//   M nu_dot + C(nu) nu + D(nu_r) nu_r + g(eta) = tau,   M = M_RB + M_A,
// with the added-mass and damping terms on the velocity relative to a constant ocean current,
// nu_r = nu - nu_c. Body frame B: x forward, y starboard, z down (NED), origin at the centre of
// origin CO; positions in the NED world frame N.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace uwgrasp::vehicle {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct Thruster {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   // in B, m
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX(); // unit thrust direction in B
};

// Rigid body, hydrodynamics and actuators. Defaults: BlueROV2 Heavy, von Benzon et al. 2022
// (config/vehicle/bluerov2_heavy.yaml cites every value).
struct VehicleParams {
  double mass = 13.5;            // kg
  double volume = 0.0134;        // displaced volume, m^3
  double rho = 1000.0;           // water density, kg/m^3
  double gravity = 9.82;         // m/s^2
  Eigen::Vector3d inertia = {0.26, 0.23, 0.37};  // Ixx, Iyy, Izz about the CG, kg m^2
  Eigen::Vector3d r_g = {0.0, 0.0, 0.0};         // centre of gravity in B, m
  Eigen::Vector3d r_b = {0.0, 0.0, -0.01};       // centre of buoyancy in B, m (1 cm above CG)
  // Positive magnitudes: M_A = diag(added_mass), D = diag(linear) + diag(quadratic .* |nu_r|).
  Vector6d added_mass = (Vector6d() << 6.3567, 7.1206, 18.6863, 0.1858, 0.1348, 0.2215).finished();
  Vector6d linear_damping = (Vector6d() << 13.7, 0.0, 33.0, 0.0, 0.8, 0.0).finished();
  Vector6d quadratic_damping = (Vector6d() << 141.0, 217.0, 190.0, 1.192, 0.470, 1.5).finished();
  std::vector<Thruster> thrusters;  // empty: the Heavy's eight (heavy_thrusters())
  double thrust_min = -40.0;        // N per thruster (reverse)
  double thrust_max = 40.0;         // N per thruster (forward)
};

// The Heavy's eight T200s placed so that their allocation matrix is von Benzon's K: four
// vectored horizontal thrusters at 45 degrees, four vertical ones at (+-0.12, +-0.218) m.
std::vector<Thruster> heavy_thrusters();
// The thrusters in use: params.thrusters, or heavy_thrusters() when empty.
std::vector<Thruster> thrusters_of(const VehicleParams& p);

// Throws Error naming the field: non-positive mass, volume, density, gravity or inertia,
// negative added mass or damping, thrust limits that do not straddle 0, a zero thrust direction.
void check_params(const VehicleParams& p);

// State: position and attitude of B in N, and body velocities nu = [u v w p q r].
struct State {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();  // R_NB
  Vector6d nu = Vector6d::Zero();
};

// M_RB (eq. 2.13 / Fossen 3.44) about CO with the CG at r_g, and M_A.
Matrix6d rigid_body_mass(const VehicleParams& p);
Matrix6d added_mass(const VehicleParams& p);
// The Coriolis-centripetal matrix of any symmetric mass matrix (Fossen 3.46 / 6.43): skew-
// symmetric for every nu, so it does no work.
Matrix6d coriolis(const Matrix6d& M, const Vector6d& nu);
// D(nu) = D_l + D_n(nu) (eq. 2.19-2.20).
Matrix6d damping(const VehicleParams& p, const Vector6d& nu);
// g(eta) (eq. 2.21-2.22, general form): weight W = m g at r_g, buoyancy B = rho g V at r_b.
Vector6d restoring(const VehicleParams& p, const Eigen::Quaterniond& attitude);
// Potential energy of weight and buoyancy (the g(eta) above is its gradient): for energy checks.
double potential_energy(const VehicleParams& p, const State& s);

// Kinematics (eq. 2.7-2.12): eta_dot = J(eta) nu for Euler angles (singular at pitch +-pi/2),
// and the quaternion form q_dot = q (x) (0, omega) / 2.
Matrix6d euler_jacobian(const Eigen::Vector3d& rpy);
Eigen::Vector4d quaternion_rate(const Eigen::Quaterniond& q, const Eigen::Vector3d& omega);

// nu_dot for thrust wrench tau (in B) and a constant current in N (m/s).
Vector6d acceleration(const VehicleParams& p, const State& s, const Vector6d& tau,
                      const Eigen::Vector3d& current);

// One fixed step of classic Runge-Kutta 4 (quaternion renormalised after the step).
State rk4_step(const VehicleParams& p, const State& s, const Vector6d& tau,
               const Eigen::Vector3d& current, double dt);

}  // namespace uwgrasp::vehicle
