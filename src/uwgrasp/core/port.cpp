#include "uwgrasp/core/port.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp {

namespace {
using V3 = Eigen::Vector3d;

void check_length(double v, const char* name) {
  if (!std::isfinite(v) || v < 0.0) throw Error(std::string("port.") + name + " must be a finite length >= 0");
}
void check_index(double v, const char* name) {
  if (!std::isfinite(v) || v < 1.0 || v > 3.0)
    throw Error(std::string("port.") + name + " must be a refractive index in [1, 3]");
}
}  // namespace

void check_port(const FlatPort& p) {
  check_length(p.distance, "distance");
  check_length(p.thickness, "thickness");
  check_index(p.n_air, "n_air");
  check_index(p.n_glass, "n_glass");
  check_index(p.n_water, "n_water");
}

std::optional<V3> refract(const V3& d, const V3& n, double n1, double n2) {
  const double eta = n1 / n2, cos_i = -n.dot(d);
  const double sin2_t = eta * eta * (1.0 - cos_i * cos_i);
  if (sin2_t > 1.0) return std::nullopt;
  return V3(eta * d + (eta * cos_i - std::sqrt(1.0 - sin2_t)) * n);
}

std::optional<PortRay> refract_through_port(const FlatPort& port, const V3& direction) {
  if (!(direction.z() > 0.0)) return std::nullopt;
  const V3 normal(0.0, 0.0, -1.0);  // both faces, facing back towards the camera
  const V3 d0 = direction.normalized();
  const V3 inner = d0 * (port.distance / d0.z());
  const auto in_glass = refract(d0, normal, port.n_air, port.n_glass);
  if (!in_glass) return std::nullopt;
  const V3 outer = inner + *in_glass * (port.thickness / in_glass->z());
  const auto in_water = refract(*in_glass, normal, port.n_glass, port.n_water);
  if (!in_water) return std::nullopt;
  return PortRay{outer, *in_water / in_water->z()};
}

std::optional<V3> direction_to(const FlatPort& port, const V3& p) {
  const double beyond = p.z() - port.distance - port.thickness;
  if (!(beyond > 0.0) || !p.allFinite()) return std::nullopt;
  const double rho = std::hypot(p.x(), p.y());
  if (rho < 1e-15) return V3(0.0, 0.0, 1.0);
  // Radial offset reached at p's depth by the ray leaving at angle a in air.
  const auto reach = [&](double a) {
    const double s = port.n_air * std::sin(a);
    const double sg = s / port.n_glass, sw = s / port.n_water;
    return port.distance * std::tan(a) + port.thickness * sg / std::sqrt(1.0 - sg * sg) +
           beyond * sw / std::sqrt(1.0 - sw * sw);
  };
  double lo = 0.0, hi = 0.5 * std::numbers::pi - 1e-9;
  // The reach grows without bound towards 90 degrees only when no face reflects totally; cap the
  // search where the water side would (n_air sin a <= n_water always holds for n_air <= n_water).
  if (port.n_air > port.n_water) hi = std::min(hi, std::asin(port.n_water / port.n_air) - 1e-9);
  if (port.n_air > port.n_glass) hi = std::min(hi, std::asin(port.n_glass / port.n_air) - 1e-9);
  if (reach(hi) < rho) return std::nullopt;
  for (int i = 0; i < 200 && hi - lo > 1e-13; ++i) {
    const double mid = 0.5 * (lo + hi);
    (reach(mid) < rho ? lo : hi) = mid;
  }
  const double t = std::tan(0.5 * (lo + hi));
  return V3(t * p.x() / rho, t * p.y() / rho, 1.0);
}

}  // namespace uwgrasp
