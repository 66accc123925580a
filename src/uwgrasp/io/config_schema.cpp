#include "uwgrasp/io/config_schema.hpp"

#include <limits>

namespace uwgrasp::io {

namespace {
constexpr double kTiny = 1e-9;  // lower bound of strictly positive quantities

void visit_preprocess(Visitor& v, cloud::PreprocessConfig& c) {
  v.section("water", [&] {
    v.field("enabled", c.water.enabled);
    v.field("attenuation", c.water.attenuation, 0.0, 100.0);
    v.field("veiling", c.water.veiling, 0.0, 1.0);
    v.field("min_transmission", c.water.min_transmission, 1e-6, 1.0);
    v.field("fallback", c.water.fallback);
  });
  v.section("range", [&] {
    v.field("enabled", c.range.enabled);
    v.field("min", c.range.min, 0.0, 1000.0);
    v.field("max", c.range.max, kTiny, 1000.0);
  });
  v.section("outliers", [&] {
    v.field("enabled", c.outliers.enabled);
    v.field("k", c.outliers.k, 1, 1000);
    v.field("std_mul", c.outliers.std_mul, 0.0, 100.0);
  });
  v.section("voxel", [&] {
    v.field("enabled", c.voxel.enabled);
    v.field("leaf", c.voxel.leaf, kTiny, 10.0);
    v.field("min_points", c.voxel.min_points, 1, 1e9);
  });
  v.section("plane", [&] {
    v.field("enabled", c.plane.enabled);
    v.field("distance", c.plane.distance, kTiny, 10.0);
    v.field("probability", c.plane.probability, kTiny, 1.0 - 1e-12);
    v.field("max_iterations", c.plane.max_iterations, 1, 1e7);
    v.field("min_inlier_ratio", c.plane.min_inlier_ratio, 0.0, 1.0);
    v.field("refine", c.plane.refine);
    v.field("required", c.plane.required);
    v.field("noise_sigmas", c.plane.noise_sigmas, 0.0, 100.0);
    v.field("normal_angle", c.plane.normal_angle, 0.0, 90.0);
    v.field("support_only", c.plane.support_only);
  });
  v.section("normals", [&] {
    v.field("k", c.normals.k, 3, 1000);
    v.field("radius", c.normals.radius, 0.0, 10.0);
  });
  v.section("organised", [&] {
    v.field("enabled", c.organised.enabled);
    v.field("half_window", c.organised.half_window, 1, 7);
    v.field("normal_half_window", c.organised.normal_half_window, 1, 7);
    v.field("max_normal_slope", c.organised.max_normal_slope, 0.0, 1.0);
    v.field("max_normal_half_window", c.organised.max_normal_half_window, 1, 7);
    v.field("depth_change", c.organised.depth_change, kTiny, 10.0);
    v.field("move_onto_quadrics", c.organised.move_onto_quadrics);
  });
}

void visit_segment(Visitor& v, segment::SegmentConfig& c) {
  v.section("region", [&] {
    v.field("k", c.region.k, 2, 1000);
    v.field("angle_deg", c.region.angle_deg, 0.0, 180.0);
    v.field("curvature", c.region.curvature, 0.0, 1.0);
    v.field("distance", c.region.distance, 0.0, 10.0);
    v.field("min_size", c.region.min_size, 1, 1e9);
    v.field("max_size", c.region.max_size, 1, 4e9);
    v.field("smooth_mode", c.region.smooth_mode);
  });
  v.section("color", [&] {
    v.field("enabled", c.color.enabled);
    v.field("point_threshold", c.color.point_threshold, 0.0, 442.0);
    v.field("region_threshold", c.color.region_threshold, 0.0, 442.0);
    v.field("merge_distance", c.color.merge_distance, 0.0, 10.0);
  });
  v.section("object", [&] {
    enum_choice<segment::ObjectBy>(v, "by", c.object.by,
                                   {{"color", segment::ObjectBy::color},
                                    {"label", segment::ObjectBy::label},
                                    {"nearest", segment::ObjectBy::nearest},
                                    {"largest", segment::ObjectBy::largest},
                                    {"point", segment::ObjectBy::point}});
    v.choice("color", c.object.color, {"red", "green", "blue", "yellow", "cyan", "magenta"});
    v.field("label", c.object.label, 0, 4e9);
    v.field("min_intensity", c.object.min_intensity, 0.0, 1.0);
    v.field("point", c.object.point, -1e4, 1e4);
    v.field("merge_radius", c.object.merge_radius, 0.0, 100.0);
    v.field("whole", c.object.whole);
    v.field("gap", c.object.gap, 0.0, 1.0);
    v.field("part_reach", c.object.part_reach, 0.0, 10.0);
    v.field("min_extent", c.object.min_extent, 0.0, 10.0);
  });
}
}  // namespace

void visit(Visitor& v, Config& c) {
  v.field("seed", c.seed);
  v.field("threads", c.threads, 0, 4096);
  v.section("stereo", [&] { visit_stereo(v, c.stereo); });
  v.section("preprocess", [&] { visit_preprocess(v, c.preprocess); });
  v.section("segment", [&] { visit_segment(v, c.segment); });
  v.section("grasp", [&] { visit_grasp(v, c.grasp); });
  v.section("sim", [&] { visit_sim(v, c.sim); });
  v.section("vehicle", [&] { visit_vehicle(v, c.vehicle); });
}

}  // namespace uwgrasp::io
