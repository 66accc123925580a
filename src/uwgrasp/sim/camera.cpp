#include "uwgrasp/sim/camera.hpp"

#include <cmath>
#include <numbers>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::sim {

void check_camera(const CameraConfig& c) {
  if (c.width < 8 || c.width > 8192) throw Error("sim.camera.width must be in [8, 8192]");
  if (c.height < 8 || c.height > 8192) throw Error("sim.camera.height must be in [8, 8192]");
  if (!(c.hfov > 0.0 && c.hfov < std::numbers::pi)) throw Error("sim.camera.hfov must be in (0, pi)");
  if (!(c.min_range > 0.0 && c.min_range < c.max_range && std::isfinite(c.max_range)))
    throw Error("sim.camera: need 0 < min_range < max_range");
  if (!(c.baseline > 0.0 && c.baseline < 10.0)) throw Error("sim.camera.baseline must be in (0, 10) m");
}

Intrinsics make_intrinsics(const CameraConfig& c) {
  check_camera(c);
  Intrinsics k;
  k.width = static_cast<int>(c.width);
  k.height = static_cast<int>(c.height);
  k.fx = k.fy = 0.5 * c.width / std::tan(0.5 * c.hfov);
  k.cx = 0.5 * (c.width - 1);
  k.cy = 0.5 * (c.height - 1);
  return k;
}

}  // namespace uwgrasp::sim
