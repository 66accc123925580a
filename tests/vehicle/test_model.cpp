// The 6-DoF model against physics: skew-symmetric C(nu), energy that only damping removes,
// restoring forces that match Fossen's closed form and oppose any tilt, and kinematics that agree.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/vehicle/model.hpp"

namespace uwgrasp::vehicle {
namespace {

Vector6d random_nu(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Vector6d v;
  for (int i = 0; i < 6; ++i) v(i) = u(rng);
  return v;
}

double energy(const VehicleParams& p, const State& s) {
  const Matrix6d M = rigid_body_mass(p) + added_mass(p);
  return 0.5 * s.nu.dot(M * s.nu) + potential_energy(p, s);
}

TEST(Model, CoriolisIsSkewSymmetricForEveryVelocity) {
  VehicleParams p;
  p.r_g = {0.01, -0.02, 0.03};  // off-centre CG: M_RB has coupling blocks
  std::mt19937 rng(3);
  for (int k = 0; k < 20; ++k) {
    const Vector6d nu = random_nu(rng, 2.0);
    for (const Matrix6d& M : {rigid_body_mass(p), added_mass(p)}) {
      const Matrix6d C = coriolis(M, nu);
      EXPECT_LT((C + C.transpose()).norm(), 1e-12);
      EXPECT_NEAR(nu.dot(C * nu), 0.0, 1e-12);  // does no work
    }
  }
}

TEST(Model, MassMatrixIsSymmetricPositiveDefinite) {
  VehicleParams p;
  p.r_g = {0.02, 0.01, 0.05};
  const Matrix6d M = rigid_body_mass(p) + added_mass(p);
  EXPECT_LT((M - M.transpose()).norm(), 1e-12);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix6d>(M).eigenvalues().minCoeff(), 0.0);
}

// No thrust, no current: kinetic + potential energy never grows, and damping takes it down.
TEST(Model, EnergyDecaysWithoutThrust) {
  VehicleParams p;
  p.r_g = {0.0, 0.0, 0.02};
  State s;
  s.nu << 0.5, -0.3, 0.2, 0.8, -0.6, 0.4;
  double e = energy(p, s);
  const double e0 = e;
  for (int i = 0; i < 2000; ++i) {
    s = rk4_step(p, s, Vector6d::Zero(), Eigen::Vector3d::Zero(), 0.01);
    const double next = energy(p, s);
    ASSERT_LE(next, e + 1e-9 * std::abs(e0)) << "step " << i;
    e = next;
  }
  EXPECT_LT(e, e0 - 0.5 * (e0 - potential_energy(p, State{})));
}

// Without damping the model conserves energy (RK4 to its truncation error).
TEST(Model, EnergyIsConservedWithoutDamping) {
  VehicleParams p;
  p.linear_damping.setZero();
  p.quadratic_damping.setZero();
  p.volume = p.mass / p.rho;  // neutral: no steady sinking to accelerate
  State s;
  s.nu << 0.3, 0.1, -0.2, 0.5, 0.4, -0.3;
  const double e0 = energy(p, s);
  for (int i = 0; i < 1000; ++i) s = rk4_step(p, s, Vector6d::Zero(), Eigen::Vector3d::Zero(), 0.005);
  EXPECT_NEAR(energy(p, s), e0, 1e-6 * std::abs(e0));
}

// g(eta) equals Fossen's closed form (2011, eq. 4.6) for any attitude and CG/CB.
TEST(Model, RestoringMatchesFossensClosedForm) {
  VehicleParams p;
  p.r_g = {0.01, -0.02, 0.015};
  p.r_b = {-0.005, 0.01, -0.03};
  const double W = p.mass * p.gravity, B = p.rho * p.gravity * p.volume;
  const Eigen::Vector3d &rg = p.r_g, &rb = p.r_b;
  for (double phi : {-1.0, -0.3, 0.0, 0.7}) {
    for (double th : {-1.2, 0.0, 0.4}) {
      const double sp = std::sin(phi), cp = std::cos(phi), st = std::sin(th), ct = std::cos(th);
      Vector6d want;
      want << (W - B) * st, -(W - B) * ct * sp, -(W - B) * ct * cp,
          -(rg.y() * W - rb.y() * B) * ct * cp + (rg.z() * W - rb.z() * B) * ct * sp,
          (rg.z() * W - rb.z() * B) * st + (rg.x() * W - rb.x() * B) * ct * cp,
          -(rg.x() * W - rb.x() * B) * ct * sp - (rg.y() * W - rb.y() * B) * st;
      const Vector6d got = restoring(p, quat_from_rpy(phi, th, 0.9));
      EXPECT_LT((got - want).norm(), 1e-9) << "phi " << phi << " theta " << th;
    }
  }
}

// CB straight above CG: no moment when level, and a moment back towards level for any tilt.
TEST(Model, RestoringMomentOpposesRollAndPitch) {
  const VehicleParams p;  // CB 1 cm above CG
  EXPECT_LT(restoring(p, Eigen::Quaterniond::Identity()).tail<3>().norm(), 1e-12);
  for (double a : {-1.2, -0.4, -0.05, 0.05, 0.4, 1.2}) {
    const Vector6d roll = -restoring(p, quat_from_rpy(a, 0, 0));   // moment on the vehicle
    const Vector6d pitch = -restoring(p, quat_from_rpy(0, a, 0));
    EXPECT_LT(roll(3) * a, 0.0) << a;
    EXPECT_LT(pitch(4) * a, 0.0) << a;
    EXPECT_NEAR(std::abs(roll(3)), p.rho * p.gravity * p.volume * 0.01 * std::sin(std::abs(a)), 1e-9);
  }
}

// Euler-angle and quaternion kinematics integrate a constant body rate to the same attitude.
TEST(Model, EulerAndQuaternionKinematicsAgree) {
  const Eigen::Vector3d omega(0.3, -0.2, 0.5);
  Eigen::Vector3d rpy(0.1, 0.2, -0.3);
  Eigen::Quaterniond q = quat_from_rpy(rpy);
  const double dt = 1e-4;
  for (int i = 0; i < 10000; ++i) {
    Vector6d nu = Vector6d::Zero();
    nu.tail<3>() = omega;
    rpy += dt * (euler_jacobian(rpy) * nu).tail<3>();
    q.coeffs() += dt * quaternion_rate(q, omega);
    q.normalize();
  }
  EXPECT_LT(q.angularDistance(quat_from_rpy(rpy)), 1e-3);
}

TEST(Model, SameInputsGiveIdenticalTrajectories) {
  const VehicleParams p;
  Vector6d tau;
  tau << 10, -3, 2, 0.5, -0.4, 1;
  State a, b;
  for (int i = 0; i < 500; ++i) {
    a = rk4_step(p, a, tau, Eigen::Vector3d(0.2, 0.1, 0), 0.01);
    b = rk4_step(p, b, tau, Eigen::Vector3d(0.2, 0.1, 0), 0.01);
  }
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.attitude.coeffs(), b.attitude.coeffs());
  EXPECT_EQ(a.nu, b.nu);
}

// A steady current carries a vehicle with no thrust along with it (nu_r -> 0 when neutral).
TEST(Model, CurrentCarriesTheVehicleAlong) {
  VehicleParams p;
  p.volume = p.mass / p.rho;
  const Eigen::Vector3d current(0.2, -0.1, 0.0);
  State s;
  for (int i = 0; i < 12000; ++i) s = rk4_step(p, s, Vector6d::Zero(), current, 0.01);
  // Sway has only quadratic damping, so the last millimetres per second go slowly.
  EXPECT_LT((s.attitude * s.nu.head<3>() - current).norm(), 2e-3);
}

TEST(Model, BadParametersAreNamed) {
  VehicleParams p;
  p.mass = 0;
  EXPECT_THROW(check_params(p), Error);
  p = {};
  p.inertia.y() = -1;
  try {
    check_params(p);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vehicle.inertia"), std::string::npos) << e.what();
  }
  p = {};
  p.quadratic_damping(2) = -5;
  EXPECT_THROW(check_params(p), Error);
  p = {};
  p.thrust_min = 1;
  EXPECT_THROW(check_params(p), Error);
}

}  // namespace
}  // namespace uwgrasp::vehicle
