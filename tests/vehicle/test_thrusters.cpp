// Thrust allocation and hold cost: the Heavy's layout reproduces von Benzon's K, feasible wrenches
// are met exactly, infeasible ones saturate along their own direction, and holding an attitude
// costs what the restoring forces ask.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/vehicle/thrusters.hpp"

namespace uwgrasp::vehicle {
namespace {

TEST(Thrusters, HeavyLayoutGivesVonBenzonsAllocationMatrix) {
  // bluerov2_heavy.yaml, von_benzon_2022.thruster_allocation_K_NED (4-decimal values).
  Eigen::Matrix<double, 6, 8> K;
  K << 0.7071, 0.7071, -0.7071, -0.7071, 0, 0, 0, 0,  //
      -0.7071, 0.7071, -0.7071, 0.7071, 0, 0, 0, 0,   //
      0, 0, 0, 0, -1, -1, -1, -1,                     //
      0, 0, 0, 0, 0.2180, 0.2180, -0.2180, -0.2180,   //
      0, 0, 0, 0, 0.1200, -0.1200, 0.1200, -0.1200,   //
      -0.1888, 0.1888, 0.1888, -0.1888, 0, 0, 0, 0;
  EXPECT_LT((allocation_matrix(heavy_thrusters()) - K).cwiseAbs().maxCoeff(), 2e-4);
}

TEST(Thrusters, FeasibleWrenchIsMetExactly) {
  const Allocator a = make_allocator(VehicleParams{});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-15, 15);
  for (int k = 0; k < 50; ++k) {
    Eigen::VectorXd f(8);
    for (int i = 0; i < 8; ++i) f(i) = u(rng);
    const Vector6d tau = a.K * f;
    const Allocation r = allocate(a, tau);
    EXPECT_LT(r.residual.norm(), 1e-9 * (1 + tau.norm()));
    EXPECT_LE(r.thrust.norm(), f.norm() + 1e-9);  // the minimum-norm solution
    EXPECT_FALSE(r.saturated());
  }
}

TEST(Thrusters, InfeasibleWrenchSaturatesAlongItsDirection) {
  const Allocator a = make_allocator(VehicleParams{});
  Vector6d tau;
  tau << 400, -100, 300, 10, -20, 40;  // far beyond eight 40 N thrusters
  const Allocation r = allocate(a, tau);
  EXPECT_TRUE(r.saturated());
  EXPECT_GT(r.utilisation, 1.0);
  EXPECT_LE(r.thrust.maxCoeff(), a.f_max + 1e-9);
  EXPECT_GE(r.thrust.minCoeff(), a.f_min - 1e-9);
  EXPECT_NEAR(r.thrust.cwiseAbs().maxCoeff(), 40.0, 1e-9);  // one thruster at its limit
  EXPECT_NEAR(r.achieved.normalized().dot(tau.normalized()), 1.0, 1e-12);
  EXPECT_NEAR(r.residual.norm(), tau.norm() * (1 - 1 / r.utilisation), 1e-9);
}

TEST(Thrusters, SingularLayoutIsAClearError) {
  VehicleParams p;
  p.thrusters = heavy_thrusters();
  p.thrusters.resize(4);  // horizontal only: no heave, roll or pitch
  EXPECT_THROW(make_allocator(p), Error);
}

// A neutrally buoyant Heavy: holding level costs nothing; tilting costs the same either way;
// yaw costs nothing without a current, and roll and pitch do.
TEST(HoldCost, ZeroAtLevelSymmetricAndFreeInYaw) {
  VehicleParams p;
  p.volume = p.mass / p.rho;
  const Allocator a = make_allocator(p);
  EXPECT_LT(hold_cost(p, a, {0, 0, 0}).utilisation(), 1e-12);
  for (double x : {0.2, 0.6, 1.0}) {
    EXPECT_NEAR(hold_cost(p, a, {x, 0, 0}).utilisation(), hold_cost(p, a, {-x, 0, 0}).utilisation(), 1e-12);
    EXPECT_NEAR(hold_cost(p, a, {0, x, 0}).utilisation(), hold_cost(p, a, {0, -x, 0}).utilisation(), 1e-12);
    EXPECT_LT(hold_cost(p, a, {0, 0, x}).utilisation(), 1e-12);
    EXPECT_GT(hold_cost(p, a, {x, 0, 0}).utilisation(), 1e-4);
    EXPECT_GT(hold_cost(p, a, {0, x, 0}).utilisation(), 1e-4);
  }
}

// Cost grows with the angle until the thrusters saturate; a vehicle with a low CG and weak
// thrusters (so that it saturates within 90 degrees) shows the whole curve.
TEST(HoldCost, GrowsMonotonicallyToSaturation) {
  VehicleParams p;
  p.volume = p.mass / p.rho;
  p.r_g = {0, 0, 0.05};
  p.thrust_min = -2;
  p.thrust_max = 2;
  const Allocator a = make_allocator(p);
  double last = -1, saturation = -1;
  for (double deg = 0; deg <= 90; deg += 1) {
    const HoldCost h = hold_cost(p, a, {deg * std::numbers::pi / 180, 0, 0});
    EXPECT_GT(h.utilisation(), last) << deg;
    EXPECT_NEAR(h.score(), std::max(0.0, 1 - h.utilisation()), 1e-12);
    if (saturation < 0 && !h.feasible()) saturation = deg;
    last = h.utilisation();
  }
  EXPECT_GT(saturation, 0);
  EXPECT_LT(saturation, 90);
}

TEST(HoldCost, CurrentCostsThrust) {
  VehicleParams p;
  p.volume = p.mass / p.rho;
  const Allocator a = make_allocator(p);
  const double still = hold_cost(p, a, {0, 0, 0}).utilisation();
  const double slow = hold_cost(p, a, {0, 0, 0}, {0.1, 0, 0}).utilisation();
  const double fast = hold_cost(p, a, {0, 0, 0}, {0.2, 0, 0}).utilisation();
  EXPECT_LT(still, slow);
  EXPECT_LT(slow, fast);
  // Head into a 0.2 m/s current: Xu u + Xuu u^2 = 13.7 * 0.2 + 141 * 0.04 = 8.38 N of surge,
  // shared by four thrusters at 45 degrees: 8.38 / (4 cos 45) each.
  EXPECT_NEAR(fast, 8.38 / (4 * std::sqrt(0.5)) / 40, 1e-3);
  // Yaw matters once there is a current: beam-on costs more than head-on (Yvv > Xuu).
  EXPECT_GT(hold_cost(p, a, {0, 0, std::numbers::pi / 2}, {0.2, 0, 0}).utilisation(), fast);
}

// The scoring function keeps a thrust vector per thread: it must give what hold_cost gives, bit
// for bit, on every thread, and switching between vehicles of other thruster counts on one
// thread must not carry one's vector into the other.
TEST(HoldCost, FunctionIsHoldCostOnEveryThreadAndVehicle) {
  VehicleParams heavy;  // with weak thrusters, so that some attitudes saturate them
  heavy.thrust_min = -4;
  heavy.thrust_max = 4;
  VehicleParams seven = heavy;  // the Heavy without one vertical thruster: still rank 6
  seven.thrusters = heavy_thrusters();
  seven.thrusters.pop_back();
  const Eigen::Vector3d current(0.15, -0.05, 0.0);
  const auto f_heavy = hold_cost_function(heavy, current);
  const auto f_seven = hold_cost_function(seven, current);
  const Allocator a_heavy = make_allocator(heavy), a_seven = make_allocator(seven);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-1.2, 1.2);
  std::vector<Eigen::Vector3d> rpys(4000);
  for (auto& r : rpys) r = {angle(rng), angle(rng), 2.0 * angle(rng)};
  std::vector<double> got_heavy(rpys.size()), got_seven(rpys.size());
  tbb::parallel_for(std::size_t(0), rpys.size(), [&](std::size_t i) {
    got_heavy[i] = f_heavy(rpys[i]);  // alternating vehicles on each thread
    got_seven[i] = f_seven(rpys[i]);
  });
  std::size_t saturated = 0;
  for (std::size_t i = 0; i < rpys.size(); ++i) {
    ASSERT_EQ(got_heavy[i], hold_cost(heavy, a_heavy, rpys[i], current).utilisation()) << i;
    ASSERT_EQ(got_seven[i], hold_cost(seven, a_seven, rpys[i], current).utilisation()) << i;
    saturated += got_seven[i] > 1.0;
  }
  EXPECT_GT(saturated, 0u);  // both sides of the bound are exercised
  EXPECT_LT(saturated, rpys.size());
}

}  // namespace
}  // namespace uwgrasp::vehicle
