#include "uwgrasp/sim/water.hpp"

#include <cmath>
#include <numbers>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::sim {

WaterConfig water_preset(const std::string& name) {
  WaterConfig w;
  w.preset = name;
  if (name == "clear") return w;  // the defaults
  if (name == "coastal") {
    w.attenuation = {0.60, 0.40, 0.55};
    w.veiling = {0.06, 0.26, 0.22};
    w.snow_density = 60.0;
    return w;
  }
  if (name == "turbid") {
    w.attenuation = {1.20, 1.10, 1.60};
    w.veiling = {0.12, 0.32, 0.22};
    w.snow_density = 300.0;
    return w;
  }
  throw Error("unknown water preset '" + name + "' (presets: clear, coastal, turbid)");
}

void check_water(const WaterConfig& w) {
  if (!w.attenuation.allFinite() || (w.attenuation.array() < 0).any())
    throw Error("sim.water.attenuation must be finite and >= 0 per channel");
  if (!w.veiling.allFinite() || (w.veiling.array() < 0).any() || (w.veiling.array() > 1).any())
    throw Error("sim.water.veiling must be in [0, 1] per channel");
  if (!(w.snow_density >= 0 && w.snow_density <= 1e5))
    throw Error("sim.water.snow_density must be in [0, 100000] per m^3");
  if (!(w.snow_radius > 0 && w.snow_radius <= 0.05))
    throw Error("sim.water.snow_radius must be in (0, 0.05] m");
  if (!(w.snow_range > 0 && w.snow_range <= 20)) throw Error("sim.water.snow_range must be in (0, 20] m");
}

void check_noise(const NoiseConfig& n) {
  if (!(n.sigma0 >= 0 && n.sigma0 < 1)) throw Error("sim.noise.sigma0 must be in [0, 1) m");
  if (!(n.sigma_k >= 0 && n.sigma_k < 1)) throw Error("sim.noise.sigma_k must be in [0, 1) 1/m");
  if (!(n.grazing_angle > 0 && n.grazing_angle <= std::numbers::pi / 2))
    throw Error("sim.noise.grazing_angle must be in (0, pi/2]");
  if (!(n.dark_threshold >= 0 && n.dark_threshold < 1))
    throw Error("sim.noise.dark_threshold must be in [0, 1)");
}

Eigen::Vector3d transmission(double d, const WaterConfig& w) {
  return (-w.attenuation.array() * d).exp().matrix();
}

Eigen::Vector3d underwater_color(const Eigen::Vector3d& J, const Eigen::Array3d& t, const WaterConfig& w) {
  return (J.array() * t + w.veiling.array() * (1.0 - t)).matrix();
}

Eigen::Vector3d underwater_color(const Eigen::Vector3d& J, double d, const WaterConfig& w) {
  return underwater_color(J, transmission(d, w).array(), w);
}

double depth_sigma(double z, const NoiseConfig& n) { return n.sigma0 + n.sigma_k * z * z; }

}  // namespace uwgrasp::sim
