#pragma once
// Water and sensor realism, which the thesis assumed away (7.4.1).
//
// Image formation (Schechner & Karpel 2005; Akkaynak & Treibitz 2018, simplified to one
// coefficient per channel): a surface of radiance J at range d appears as
//     I_c = J_c exp(-c_c d) + B_c (1 - exp(-c_c d)),   c = R, G, B,
// the direct signal attenuated by the beam attenuation coefficient c_c (1/m), plus veiling light
// (backscatter) that saturates at B_c with range. The presets' coefficients are representative
// of Jerlov's water types (Jerlov 1976; inherent optical properties tabulated by Solonenko &
// Mobley 2015, Applied Optics 54(17)), rounded, and within the range Akkaynak et al. 2017 (CVPR)
// report for underwater imaging; they are not fitted to one measurement:
//   clear   ~ Jerlov I   (open ocean):   c = 0.30, 0.07, 0.04 /m; faint blue veiling light
//   coastal ~ Jerlov 3C  (coastal):      c = 0.60, 0.40, 0.55 /m; green veiling light
//   turbid  ~ Jerlov 9C  (harbour, fjord after rain): c = 1.20, 1.10, 1.60 /m
// Marine snow densities (particles >= 0.5 mm per m^3) follow the order of magnitude of
// in-situ counts (Alldredge & Silver 1988, Prog. Oceanogr. 20): a few to hundreds per m^3.
//
// Depth sensor: noise along the ray with sigma(z) = sigma0 + sigma_k z^2 (structured-light and
// stereo depth error grows with z^2; Nguyen, Izadi & Lovell 2012 measured 1.2 mm + 1.9 mm/m^2
// for the Kinect). Dropouts where the surface is seen at a grazing angle and where the direct
// signal returning from it is too dark. `clear` water with the noise off is the thesis's perfect
// sensor: exact depth for every pixel in range, no particles.
#include <Eigen/Core>
#include <string>

namespace uwgrasp::sim {

struct WaterConfig {
  std::string preset = "clear";
  Eigen::Vector3d attenuation{0.30, 0.07, 0.04};  // c per R, G, B, 1/m
  Eigen::Vector3d veiling{0.02, 0.10, 0.18};      // B per R, G, B, in [0, 1]
  double snow_density = 5.0;                      // particles per m^3
  double snow_radius = 0.002;                     // m (mean; radii vary 0.5x-1.5x)
  double snow_range = 3.0;                        // particles are placed up to this range, m
};

struct NoiseConfig {
  bool enabled = true;
  double sigma0 = 0.0012;         // m
  double sigma_k = 0.0019;        // 1/m
  double grazing_angle = 1.22;    // rad from the surface normal where dropouts start (70 deg)
  double dark_threshold = 0.03;   // direct signal (0-1) below which depth drops out
};

// The named preset (clear, coastal, turbid); Throws Error listing them for another name.
WaterConfig water_preset(const std::string& name);
// Throws Error naming the field for negative or non-finite coefficients, veiling light outside
// [0, 1], or a particle radius outside (0, 5 cm].
void check_water(const WaterConfig& w);
void check_noise(const NoiseConfig& n);

// The formation law above for one surface colour J (0-1 per channel) at range d.
Eigen::Vector3d underwater_color(const Eigen::Vector3d& J, double d, const WaterConfig& w);
// The same law for a known transmission t = exp(-c d).
Eigen::Vector3d underwater_color(const Eigen::Vector3d& J, const Eigen::Array3d& t, const WaterConfig& w);
// Transmission exp(-c d) per channel.
Eigen::Vector3d transmission(double d, const WaterConfig& w);
double depth_sigma(double z, const NoiseConfig& n);

}  // namespace uwgrasp::sim
