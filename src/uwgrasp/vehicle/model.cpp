#include "uwgrasp/vehicle/model.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/pose.hpp"

namespace uwgrasp::vehicle {

namespace {
Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d S;
  S << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return S;
}

void require(bool ok, const std::string& field, double value, const char* what) {
  if (!ok) throw Error("vehicle." + field + " = " + std::to_string(value) + ": " + what);
}

struct Derivative {
  Eigen::Vector3d position;
  Eigen::Vector4d attitude;  // quaternion coefficients (x, y, z, w)
  Vector6d nu;
};

Derivative derivative(const VehicleParams& p, const State& s, const Vector6d& tau,
                      const Eigen::Vector3d& current) {
  const Eigen::Quaterniond q = s.attitude.normalized();
  return {q * s.nu.head<3>(), quaternion_rate(q, s.nu.tail<3>()), acceleration(p, s, tau, current)};
}

State advance(const State& s, const Derivative& d, double dt) {
  State out;
  out.position = s.position + dt * d.position;
  out.attitude.coeffs() = s.attitude.coeffs() + dt * d.attitude;
  out.attitude.normalize();
  out.nu = s.nu + dt * d.nu;
  return out;
}
}  // namespace

std::vector<Thruster> heavy_thrusters() {
  // Von Benzon's K fixes |x| + |y| = 0.267 m for the horizontal thrusters; the split follows the
  // Gazebo model's 0.14 : 0.092 (bluerov2_heavy.yaml), to the millimetre. Vertical ones thrust
  // upwards (-z).
  const double hx = 0.161, hy = 0.106, c = std::sqrt(0.5);
  return {
      {{hx, hy, 0}, {c, -c, 0}},    {{hx, -hy, 0}, {c, c, 0}},
      {{-hx, hy, 0}, {-c, -c, 0}},  {{-hx, -hy, 0}, {-c, c, 0}},
      {{0.12, -0.218, 0}, {0, 0, -1}}, {{-0.12, -0.218, 0}, {0, 0, -1}},
      {{0.12, 0.218, 0}, {0, 0, -1}},  {{-0.12, 0.218, 0}, {0, 0, -1}},
  };
}

std::vector<Thruster> thrusters_of(const VehicleParams& p) {
  return p.thrusters.empty() ? heavy_thrusters() : p.thrusters;
}

void check_params(const VehicleParams& p) {
  require(p.mass > 0, "mass", p.mass, "must be positive");
  require(p.volume > 0, "volume", p.volume, "must be positive");
  require(p.rho > 0, "rho", p.rho, "must be positive");
  require(p.gravity > 0, "gravity", p.gravity, "must be positive");
  for (int i = 0; i < 3; ++i)
    require(p.inertia[i] > 0, "inertia", p.inertia[i], "every moment of inertia must be positive");
  for (int i = 0; i < 6; ++i) {
    require(p.added_mass[i] >= 0, "added_mass", p.added_mass[i], "magnitudes must be >= 0");
    require(p.linear_damping[i] >= 0, "linear_damping", p.linear_damping[i], "magnitudes must be >= 0");
    require(p.quadratic_damping[i] >= 0, "quadratic_damping", p.quadratic_damping[i], "magnitudes must be >= 0");
  }
  require(p.thrust_min < 0, "thrust.min", p.thrust_min, "must be negative (reverse thrust)");
  require(p.thrust_max > 0, "thrust.max", p.thrust_max, "must be positive");
  for (std::size_t i = 0; i < p.thrusters.size(); ++i)
    require(p.thrusters[i].direction.norm() > 1e-9 && p.thrusters[i].position.allFinite(),
            "thrusters.t" + std::to_string(i + 1) + ".direction", p.thrusters[i].direction.norm(),
            "must be finite and not zero");
}

Matrix6d rigid_body_mass(const VehicleParams& p) {
  const Eigen::Matrix3d S = skew(p.r_g);
  Matrix6d M;
  M << p.mass * Eigen::Matrix3d::Identity(), -p.mass * S,
       p.mass * S, Eigen::Matrix3d(p.inertia.asDiagonal()) - p.mass * S * S;
  return M;
}

Matrix6d added_mass(const VehicleParams& p) { return p.added_mass.asDiagonal(); }

Matrix6d coriolis(const Matrix6d& M, const Vector6d& nu) {
  const Eigen::Vector3d a1 = M.topLeftCorner<3, 3>() * nu.head<3>() + M.topRightCorner<3, 3>() * nu.tail<3>();
  const Eigen::Vector3d a2 = M.bottomLeftCorner<3, 3>() * nu.head<3>() + M.bottomRightCorner<3, 3>() * nu.tail<3>();
  Matrix6d C = Matrix6d::Zero();
  C.topRightCorner<3, 3>() = -skew(a1);
  C.bottomLeftCorner<3, 3>() = -skew(a1);
  C.bottomRightCorner<3, 3>() = -skew(a2);
  return C;
}

Matrix6d damping(const VehicleParams& p, const Vector6d& nu) {
  return Matrix6d((p.linear_damping + p.quadratic_damping.cwiseProduct(nu.cwiseAbs())).asDiagonal());
}

Vector6d restoring(const VehicleParams& p, const Eigen::Quaterniond& attitude) {
  const Eigen::Matrix3d Rt = attitude.normalized().toRotationMatrix().transpose();
  const double W = p.mass * p.gravity, B = p.rho * p.gravity * p.volume;
  const Eigen::Vector3d f_g = Rt * Eigen::Vector3d(0, 0, W), f_b = Rt * Eigen::Vector3d(0, 0, -B);
  Vector6d g;
  g << -(f_g + f_b), -(p.r_g.cross(f_g) + p.r_b.cross(f_b));
  return g;
}

double potential_energy(const VehicleParams& p, const State& s) {
  const Eigen::Matrix3d R = s.attitude.normalized().toRotationMatrix();
  const double W = p.mass * p.gravity, B = p.rho * p.gravity * p.volume;
  // NED: z grows downwards, so weight loses potential as the CG sinks and buoyancy gains it.
  return -W * (s.position.z() + (R * p.r_g).z()) + B * (s.position.z() + (R * p.r_b).z());
}

Matrix6d euler_jacobian(const Eigen::Vector3d& rpy) {
  const double sp = std::sin(rpy.x()), cp = std::cos(rpy.x()), ct = std::cos(rpy.y()), tt = std::tan(rpy.y());
  Eigen::Matrix3d T;
  T << 1, sp * tt, cp * tt, 0, cp, -sp, 0, sp / ct, cp / ct;
  Matrix6d J = Matrix6d::Zero();
  J.topLeftCorner<3, 3>() = quat_from_rpy(rpy).toRotationMatrix();
  J.bottomRightCorner<3, 3>() = T;
  return J;
}

Eigen::Vector4d quaternion_rate(const Eigen::Quaterniond& q, const Eigen::Vector3d& omega) {
  const Eigen::Quaterniond w(0, omega.x(), omega.y(), omega.z());
  return 0.5 * (q * w).coeffs();
}

Vector6d acceleration(const VehicleParams& p, const State& s, const Vector6d& tau,
                      const Eigen::Vector3d& current) {
  const Eigen::Quaterniond q = s.attitude.normalized();
  const Eigen::Vector3d vc = q.conjugate() * current;  // current in B
  Vector6d nu_c = Vector6d::Zero(), nu_c_dot = Vector6d::Zero();
  nu_c.head<3>() = vc;
  nu_c_dot.head<3>() = -s.nu.tail<3>().cross(vc);  // d/dt (R^T v_c) for a current constant in N
  const Vector6d nu_r = s.nu - nu_c;
  const Matrix6d M_rb = rigid_body_mass(p), M_a = added_mass(p);
  const Vector6d rhs = tau - coriolis(M_rb, s.nu) * s.nu - coriolis(M_a, nu_r) * nu_r -
                       damping(p, nu_r) * nu_r - restoring(p, q) + M_a * nu_c_dot;
  return (M_rb + M_a).ldlt().solve(rhs);
}

State rk4_step(const VehicleParams& p, const State& s, const Vector6d& tau,
               const Eigen::Vector3d& current, double dt) {
  const Derivative k1 = derivative(p, s, tau, current);
  const Derivative k2 = derivative(p, advance(s, k1, dt / 2), tau, current);
  const Derivative k3 = derivative(p, advance(s, k2, dt / 2), tau, current);
  const Derivative k4 = derivative(p, advance(s, k3, dt), tau, current);
  const Derivative sum{(k1.position + 2 * k2.position + 2 * k3.position + k4.position) / 6,
                       (k1.attitude + 2 * k2.attitude + 2 * k3.attitude + k4.attitude) / 6,
                       (k1.nu + 2 * k2.nu + 2 * k3.nu + k4.nu) / 6};
  return advance(s, sum, dt);
}

}  // namespace uwgrasp::vehicle
