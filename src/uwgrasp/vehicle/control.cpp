#include "uwgrasp/vehicle/control.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::vehicle {

namespace {
// Minimum-jerk profile and its first two derivatives in tau = t / T.
struct Profile {
  double s = 0, ds = 0, dds = 0;
};
Profile min_jerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  const double t2 = tau * tau, t3 = t2 * tau;
  return {10 * t3 - 15 * t3 * tau + 6 * t3 * t2, 30 * t2 - 60 * t3 + 30 * t2 * t2,
          60 * tau - 180 * t2 + 120 * t3};
}
constexpr double kPeak = 1.875;  // max of ds/dtau
}  // namespace

void check_control(const ControlConfig& c) {
  const auto need = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw Error(std::string("vehicle.control.") + name + " = " + std::to_string(v) + ": must be positive");
  };
  need(c.position_bandwidth, "position_bandwidth");
  need(c.attitude_bandwidth, "attitude_bandwidth");
  need(c.transit_speed, "transit_speed");
  need(c.approach_speed, "approach_speed");
  need(c.turn_rate, "turn_rate");
  need(c.dt, "dt");
  need(c.max_time, "max_time");
  need(c.position_tolerance, "position_tolerance");
  need(c.attitude_tolerance, "attitude_tolerance");
  need(c.hold_time, "hold_time");
}

Segment make_segment(const Eigen::Vector3d& from, const Eigen::Quaterniond& q_from,
                     const Eigen::Vector3d& to, const Eigen::Quaterniond& q_to, double speed,
                     double turn_rate) {
  Segment s{from, to, q_from.normalized(), q_to.normalized(), 0.0};
  if (s.q_from.dot(s.q_to) < 0.0) s.q_to.coeffs() = -s.q_to.coeffs();  // the short way round
  const double angle = s.q_from.angularDistance(s.q_to);
  s.duration = kPeak * std::max((to - from).norm() / speed, angle / turn_rate);
  return s;
}

Reference reference_at(const Segment& s, double t) {
  Reference r;
  if (!(s.duration > 0.0)) {
    r.position = s.to, r.attitude = s.q_to;
    return r;
  }
  const Profile p = min_jerk(t / s.duration);
  const double T = s.duration;
  const Eigen::Vector3d d = s.to - s.from;
  r.position = s.from + p.s * d;
  r.velocity = p.ds / T * d;
  r.acceleration = p.dds / (T * T) * d;
  r.attitude = s.q_from.slerp(p.s, s.q_to);
  // Slerp turns about one fixed axis (the same in the start and end body frames).
  const Eigen::AngleAxisd turn(s.q_from.conjugate() * s.q_to);
  r.omega = p.ds / T * turn.angle() * turn.axis();
  r.alpha = p.dds / (T * T) * turn.angle() * turn.axis();
  return r;
}

Vector6d pose_error(const State& s, const Eigen::Vector3d& position, const Eigen::Quaterniond& q) {
  Vector6d e;
  e.head<3>() = s.attitude.conjugate() * (position - s.position);
  Eigen::Quaterniond qe = s.attitude.conjugate() * q;
  if (qe.w() < 0.0) qe.coeffs() = -qe.coeffs();
  const Eigen::AngleAxisd aa(qe);
  e.tail<3>() = aa.angle() * aa.axis();
  return e;
}

Controller make_controller(const VehicleParams& p, const ControlConfig& c) {
  check_control(c);
  Controller k;
  k.M = rigid_body_mass(p) + added_mass(p);
  for (int i = 0; i < 6; ++i) {
    const double w = i < 3 ? c.position_bandwidth : c.attitude_bandwidth, m = k.M(i, i);
    k.kp[i] = 3 * m * w * w, k.kd[i] = 3 * m * w, k.ki[i] = m * w * w * w;
  }
  return k;
}

Vector6d control(Controller& k, const VehicleParams& p, const State& s, const Reference& r,
                 double dt, bool saturated) {
  const Vector6d e = pose_error(s, r.position, r.attitude);
  Vector6d nu_ref, nu_dot_ref;
  nu_ref << s.attitude.conjugate() * r.velocity, r.omega;
  nu_dot_ref << s.attitude.conjugate() * r.acceleration, r.alpha;
  if (!saturated) k.integral += dt * e;
  // Feedforward of what the reference needs (inertia and drag on the reference velocity, the
  // current being unknown to the controller) and of the restoring forces g(eta).
  const Vector6d feedforward =
      k.M * nu_dot_ref + damping(p, nu_ref) * nu_ref + restoring(p, s.attitude);
  return feedforward + k.kp.cwiseProduct(e) + k.kd.cwiseProduct(nu_ref - s.nu) +
         k.ki.cwiseProduct(k.integral);
}

}  // namespace uwgrasp::vehicle
