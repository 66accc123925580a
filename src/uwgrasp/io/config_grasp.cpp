// The grasp section of the config schema (gripper, frames, sampler, scoring).
#include <numbers>

#include "uwgrasp/io/config_schema.hpp"

namespace uwgrasp::io {

namespace {
constexpr double kTiny = 1e-9;
constexpr double kPi = std::numbers::pi;

void visit_gripper(Visitor& v, grasp::GripperConfig& g) {
  v.field("max_aperture", g.max_aperture, kTiny, 10.0);
  v.field("min_aperture", g.min_aperture, 0.0, 10.0);
  v.field("finger_length", g.finger_length, kTiny, 10.0);
  v.field("finger_width", g.finger_width, kTiny, 10.0);
  v.field("finger_height", g.finger_height, kTiny, 10.0);
  v.field("palm_depth", g.palm_depth, kTiny, 10.0);
  v.field("palm_height", g.palm_height, kTiny, 10.0);
  v.field("body_length", g.body_length, kTiny, 10.0);
  v.field("body_width", g.body_width, kTiny, 10.0);
  v.field("body_height", g.body_height, kTiny, 10.0);
  v.field("clearance", g.clearance, 0.0, 10.0);
}

void visit_mount(Visitor& v, const char* name, grasp::Mount& m) {
  v.section(name, [&] {
    v.field("position", m.position, -100.0, 100.0);
    v.field("rpy", m.rpy, -2 * kPi, 2 * kPi);
  });
}

void visit_frames(Visitor& v, grasp::FrameConfig& f) {
  visit_mount(v, "camera", f.camera);
  visit_mount(v, "gripper", f.gripper);
  v.field("capture_roll", f.capture_roll, -kPi, kPi);
  v.field("capture_pitch", f.capture_pitch, -kPi / 2, kPi / 2);
  using L = grasp::FrameConfig::Level;  // "true" / "false": a YAML bool, as before "auto" existed
  enum_choice<L>(v, "level_from_floor", f.level_from_floor,
                 {{"auto", L::automatic}, {"true", L::floor}, {"false", L::attitude}});
}

void visit_sampler(Visitor& v, grasp::SamplerConfig& s) {
  using K = grasp::SamplerKind;
  enum_choice<K>(v, "kind", s.kind,
                 {{"normal", K::normal}, {"uniform", K::uniform}, {"surface", K::surface},
                  {"antipodal", K::antipodal}, {"auto", K::automatic}});
  v.field("samples", s.samples, 1, 1e8);
  v.field("sigma_theta", s.sigma_theta, 0.0, 2 * kPi);
  v.field("variations", s.variations, 1, 1e6);
  v.field("sigma_p", s.sigma_p, 0.0, 10.0);
  v.field("alpha_p", s.alpha_p, 0.0, 100.0);
  v.field("pilot", s.pilot, 0.01, 1.0 / 3.0);
  v.field("sigma_tilt", s.sigma_tilt, 0.0, kPi);
  v.field("enough", s.enough, 0, 1e8);
  v.field("turns", s.turns, 1, 360);
  v.field("focus", s.focus);
  v.field("floor_clearance", s.floor_clearance, 0.0, 1.0);
}

void visit_shape(Visitor& v, grasp::ShapeConfig& s) {
  v.field("enabled", s.enabled);
  v.field("voxel", s.voxel, 1e-4, 1.0);
  v.field("max_voxels", s.max_voxels, 1000, 1e9);
  v.field("min_thickness", s.min_thickness, 0.0, 1.0);
  v.field("shadow_tolerance", s.shadow_tolerance, 0.0, 1.0);
  v.field("floor_clearance", s.floor_clearance, 0.0, 1.0);
  v.field("resolution", s.resolution, 1e-4, 0.1);
  v.field("margin_sigmas", s.margin_sigmas, 0.0, 100.0);
  v.field("min_margin", s.min_margin, 0.0, 0.1);
  v.field("depth_error", s.depth_error, 0.0, 1.0);
  v.section("symmetry", [&] {
    grasp::SymmetryConfig& m = s.symmetry;
    v.field("enabled", m.enabled);
    v.field("angle_step", m.angle_step, 0.005, 0.8);
    v.field("max_tilt", m.max_tilt, 0.0, 1.5);
    v.field("tilt_margin", m.tilt_margin, 0.0, 10.0);
    v.field("offset_step", m.offset_step, 1e-4, 0.05);
    v.field("samples", m.samples, 10, 1e6);
    v.field("tolerance", m.tolerance, 0.0, 0.1);
    v.field("noise_sigmas", m.noise_sigmas, 0.0, 100.0);
    v.field("violation_weight", m.violation_weight, 0.0, 1000.0);
    v.field("max_violations", m.max_violations, 0.0, 1.0);
    v.field("min_support", m.min_support, 0.0, 1.0);
    v.field("perpendicular", m.perpendicular);
  });
}

void visit_score(Visitor& v, grasp::ScoreConfig& s) {
  using SM = grasp::ScoreMode;
  enum_choice<SM>(v, "mode", s.mode, {{"robust", SM::robust}, {"thesis", SM::thesis}});
  v.section("robust", [&] {
    v.field("mu", s.robust.mu, 1e-3, 100.0);
    // At least one of each: robust mode offers only grasps it measured (mode thesis measures none).
    v.field("samples", s.robust.samples, 1, 1e5);
    v.field("candidates", s.robust.candidates, 1, 1e6);
    v.field("refine", s.robust.refine, 0, 1e6);
    v.field("refine_samples", s.robust.refine_samples, 0, 1e5);
    v.field("sigma_position", s.robust.sigma_position, 0.0, 1.0);
    v.field("sigma_angle", s.robust.sigma_angle, 0.0, kPi);
    v.field("core_friction", s.robust.core_friction);
    v.field("min_robustness", s.robust.min_robustness, 0.0, 1.0);
    v.field("scene", s.robust.scene);
  });
  v.section("weights", [&] {
    v.field("normal", s.weights.normal, 0.0, 1e6);
    v.field("orientation", s.weights.orientation, 0.0, 1e6);
    v.field("contact", s.weights.contact, 0.0, 1e6);
    v.field("inliers", s.weights.inliers, 0.0, 1e6);
    v.field("vehicle", s.weights.vehicle, 0.0, 1e6);
  });
  v.section("orientation", [&] {
    using F = grasp::OrientationForm;
    enum_choice<F>(v, "form", s.orientation.form, {{"monotone", F::monotone}, {"thesis", F::thesis}});
    v.field("roll", s.orientation.roll, 0.0, 1e6);
    v.field("pitch", s.orientation.pitch, 0.0, 1e6);
    v.field("yaw", s.orientation.yaw, 0.0, 1e6);
  });
  v.section("inliers", [&] {
    using M = grasp::InlierMode;
    enum_choice<M>(v, "mode", s.inlier_mode,
                   {{"fixed", M::fixed}, {"volume", M::volume}, {"surface", M::surface}});
    v.field("max", s.max_inliers, 1.0, 1e9);
    v.field("min", s.min_inliers, 1, 1e9);
  });
  v.section("friction", [&] {
    v.field("mu", s.mu, 0.0, 100.0);
    v.field("required", s.require_antipodal);
  });
  v.field("top", s.top, 1, 1e6);
}
}  // namespace

void visit_grasp(Visitor& v, grasp::GraspConfig& c) {
  v.section("gripper", [&] { visit_gripper(v, c.gripper); });
  v.section("frames", [&] { visit_frames(v, c.frames); });
  v.section("sampler", [&] { visit_sampler(v, c.sampler); });
  v.section("shape", [&] { visit_shape(v, c.shape); });
  v.section("occlusion", [&] {
    v.field("enabled", c.occlusion.enabled);
    v.field("thickness", c.occlusion.thickness, 0.0, 10.0);
    v.field("tolerance", c.occlusion.tolerance, 0.0, 1.0);
    v.field("resolution", c.occlusion.resolution, 1e-4, 0.1);
    v.field("spacing", c.occlusion.spacing, 1e-3, 1.0);
  });
  v.section("reach", [&] {
    v.field("enabled", c.reach.enabled);
    v.field("hull_size", c.reach.hull_size, kTiny, 100.0);
    v.field("hull_centre", c.reach.hull_centre, -100.0, 100.0);
    v.field("standoff", c.reach.standoff, 0.0, 100.0);
    v.field("margin", c.reach.margin, 0.0, 10.0);
    v.field("floor_tolerance", c.reach.floor_tolerance, 0.0, 10.0);
    v.field("debris_size", c.reach.debris_size, 0.0, 10.0);
    v.field("debris_gap", c.reach.debris_gap, 1e-4, 1.0);
    v.field("columns", c.reach.columns);
  });
  v.section("score", [&] { visit_score(v, c.score); });
}

}  // namespace uwgrasp::io
