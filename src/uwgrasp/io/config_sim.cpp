// The sim section of the config schema (virtual camera, water preset, depth-sensor noise), and
// the stereo section (the real stereo matcher that turns pairs into clouds).
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

void visit_stereo(Visitor& v, camera::DenseConfig& c) {
  v.field("min_range", c.min_range, 1e-3, 1000.0);
  v.field("max_range", c.max_range, 1e-3, 1000.0);
  v.field("max_disparities", c.max_disparities, 16, 1024);
  v.field("block_size", c.block_size, 1, 21);
  v.field("uniqueness", c.uniqueness, 0, 100);
  v.field("left_right_check", c.left_right_check);
  v.field("lr_max_diff", c.lr_max_diff, 0, 64);
  v.field("speckle_window", c.speckle_window, 0, 100000);
  v.field("speckle_range", c.speckle_range, 0, 64);
  v.field("downscale", c.downscale, 1, 4);
  v.choice("mode", c.mode, {"3way", "sgbm", "hh"});
  v.field("port_reference", c.port_reference, 1e-3, 1000.0);
  v.field("disparity_sigma", c.disparity_sigma, 0.0, 10.0);
}

}  // namespace uwgrasp::io
