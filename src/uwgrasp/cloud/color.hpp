#pragma once
// Underwater colour restoration (not in the thesis, which assumed clear water, 7.4.1). Water
// attenuates red first, so at a metre or two a red object no longer looks red and colour-based
// object selection (7.4.2) fails. Inverting the image formation model of sim/water.hpp
// (Schechner & Karpel 2005, one coefficient per channel),
//     I = J t + B (1 - t),   t = exp(-c d),   so   J = (I - B (1 - t)) / t,
// with d the point's distance from the viewpoint, gives each point the colour it would have out
// of the water. The coefficients are the water's: measure them (a colour chart at two ranges) or
// take a preset's.
#include <Eigen/Core>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::cloud {

struct WaterColorConfig {
  bool enabled = false;
  Eigen::Vector3d attenuation{0.30, 0.07, 0.04};  // c per R, G, B, 1/m (the clear preset's)
  Eigen::Vector3d veiling{0.02, 0.10, 0.18};      // B per R, G, B, 0-1
  double min_transmission = 0.02;  // below this t a channel is noise: it is clamped to t = this
  // With restoration off, selecting the object by colour restores the colours (with the
  // coefficients above) when no object has the colour without: water takes red first, and a red
  // object 1.2 m away in turbid water is red no more. The defaults are clear water's, the least
  // natural water attenuates, so elsewhere the restored colours fall short of the true ones.
  bool fallback = true;
};

// Restores the colours of `cloud` in place (no-op without colours). Throws Error naming the
// field for negative or non-finite coefficients, veiling light outside [0, 1] or a minimum
// transmission outside (0, 1].
void restore_colors(Cloud& cloud, const WaterColorConfig& cfg);

}  // namespace uwgrasp::cloud
