// The sim section of the config schema (virtual camera, water preset, depth-sensor noise).
#include <numbers>

#include "uwgrasp/io/config_schema.hpp"

namespace uwgrasp::io {

void visit_sim(Visitor& v, SimConfig& c) {
  constexpr double kPi = std::numbers::pi;
  v.section("camera", [&] {
    v.field("width", c.camera.width, 8, 8192);
    v.field("height", c.camera.height, 8, 8192);
    v.field("hfov", c.camera.hfov, 1e-3, kPi - 1e-3);
    v.field("max_range", c.camera.max_range, 1e-3, 1000.0);
    v.field("min_range", c.camera.min_range, 1e-3, 1000.0);
    v.field("baseline", c.camera.baseline, 1e-3, 10.0);
  });
  v.choice("water", c.water, {"clear", "coastal", "turbid"});
  v.section("noise", [&] {
    v.field("enabled", c.noise.enabled);
    v.field("sigma0", c.noise.sigma0, 0.0, 0.999);
    v.field("sigma_k", c.noise.sigma_k, 0.0, 0.999);
    v.field("grazing_angle", c.noise.grazing_angle, 1e-3, kPi / 2);
    v.field("dark_threshold", c.noise.dark_threshold, 0.0, 0.999);
  });
}

}  // namespace uwgrasp::io
