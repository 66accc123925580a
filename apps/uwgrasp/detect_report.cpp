// What `uwgrasp detect` prints and draws about one detection (detect_report.hpp).
#include "detect_report.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "app/simulation.hpp"

namespace uwgrasp::app {

namespace {
double deg(double rad) { return rad * 180.0 / std::numbers::pi; }

// A seafloor this far from the configured level is worth a line: more than a seafloor's own
// slope usually is, as a camera pitched at a table with no attitude given puts it.
constexpr double kHintTilt = 0.2618;  // rad, 15 degrees

void print_vec(const char* label, const Eigen::Vector3d& v, const char* unit) {
  std::printf("%s(%8.4f, %8.4f, %8.4f)%s", label, v.x(), v.y(), v.z(), unit);
}

void print_best(const grasp::Grasp& g, const grasp::Frames& f, const grasp::ScoreConfig& s) {
  const Pose T_CG = grasp::camera_from_gripper(g, f);
  const Eigen::Quaterniond q(T_CG.linear());
  std::printf("best grasp: score %.3f\n", g.scores.total);
  print_vec("  camera frame   position ", T_CG.translation(), " m");
  std::printf("  orientation xyzw (%.4f, %.4f, %.4f, %.4f)\n", q.x(), q.y(), q.z(), q.w());
  print_vec("                 approach ", T_CG.linear().col(0), "");
  print_vec("  closing ", T_CG.linear().col(1), "\n");
  print_vec("  level frame    position ", g.level_from_gripper.translation(), " m");
  print_vec("  rpy ", rpy_from_matrix(g.level_from_gripper.linear()) * (180.0 / std::numbers::pi),
            " deg\n");
  print_vec("  vehicle pose   position ", g.level_from_vehicle.translation(), " m");
  print_vec("  rpy ", g.vehicle_rpy * (180.0 / std::numbers::pi), " deg\n");
  if (std::isfinite(g.hold_cost))
    std::printf("  holding it takes %.1f %% of the thrusters' limit (q_v %.3f)\n",
                100 * g.hold_cost, g.scores.vehicle);
  std::printf(
      "  scores         normal %.3f  orientation %.3f  contact left %.3f right %.3f  "
      "inliers %.3f\n",
      g.scores.normal, g.scores.orientation, g.scores.contact_left, g.scores.contact_right,
      g.scores.inliers);
  std::printf("  width %.4f m, %zu inliers, %s for mu %.2f (needs mu >= %.3f)\n", g.width,
              g.inliers, g.friction.ok ? "antipodal" : "not antipodal", s.mu,
              g.friction.mu_required);
  if (s.mode == grasp::ScoreMode::robust)
    std::printf(
        "  on the object's model: holds at mu %.2f in %.0f %% of %u poses perturbed by %.0f mm and "
        "%.0f deg (q_fc %.3f); contacts %s and %s\n",
        s.robust.mu, 100 * g.robustness, g.robust_poses, 1000 * s.robust.sigma_position,
        s.robust.sigma_angle * 180 / std::numbers::pi, g.force_closure,
        g.contact_seen[0] ? "seen" : "unseen", g.contact_seen[1] ? "seen" : "unseen");
}

// Why there is no grasp. When feasible candidates remain, "N feasible" above would read as a
// contradiction of "no feasible grasp": the best-predicted all failed their robustness test.
void print_none(const grasp::ObjectGrasps& r) {
  const std::size_t weak = r.rejections[static_cast<int>(grasp::Reject::not_robust)];
  std::printf("no feasible grasp");
  if (weak > 0)
    std::printf(
        ": the %zu best-predicted candidates held on the object's model in too few of their "
        "perturbed poses (not_robust)",
        weak);
  if (weak > 0 && r.feasible() > 0)
    std::printf(
        "; the %zu feasible ones ranked below them are not measured or offered "
        "(grasp.score.robust.candidates)",
        r.feasible());
  std::printf("\n");
}
}  // namespace

void print_level(const grasp::Detection& d, const grasp::FrameConfig& f) {
  const auto& plane = d.scene.pre.plane;
  if (grasp::levels_from_floor(f)) {
    const bool asked = f.level_from_floor == grasp::FrameConfig::Level::floor;
    if (d.floor_attitude)
      std::printf("level: roll %.1f, pitch %.1f deg from the seafloor plane (%s)\n",
                  deg(d.floor_attitude->roll), deg(d.floor_attitude->pitch),
                  asked ? "grasp.frames.level_from_floor"
                        : "no capture attitude given; grasp.frames.level_from_floor=auto");
    else
      std::printf(
          "level: no seafloor plane within %.0f deg of the configured level; capture_roll/pitch as "
          "configured\n",
          deg(grasp::kMaxFloorTilt));
    return;
  }
  const auto tilt = plane.found ? grasp::floor_tilt(plane.coefficients, f) : std::nullopt;
  if (tilt && *tilt > kHintTilt && *tilt <= grasp::kMaxFloorTilt)
    std::printf(
        "level: the seafloor plane is %.0f deg from level as configured (capture_roll/pitch, "
        "the camera's mount); a frame with no attitude: --set grasp.frames.level_from_floor=true\n",
        deg(*tilt));
}

void print_detection(const std::string& name, const grasp::Detection& d, const io::Config& cfg,
                     const io::OutputFrame& frame) {
  const auto& r = d.result;
  const Eigen::Vector3d c = centroid(d.object);
  std::printf("%s: %zu points in, %zu after preprocessing, %zu segments\n", name.c_str(),
              d.scene.pre.counts.input, d.scene.pre.counts.output, d.scene.info.size());
  if (d.scene.pre.organised)
    std::printf("normals: %s\n", cloud::normals_summary(d.scene.pre).c_str());
  std::printf("object: segment %zu, %zu points, centroid (%.3f, %.3f, %.3f) m\n", d.segment,
              d.object.size(), c.x(), c.y(), c.z());
  if (d.restored_colours)
    std::printf(
        "object: no %s object in the colours as seen; selected in the colours restored with "
        "preprocess.water's coefficients (preprocess.water.fallback)\n",
        cfg.segment.object.color.c_str());
  if (!r.shape.empty()) {
    std::printf("shape: %zu seen points, surface noise %.1f mm", d.object.size(),
                1e3 * r.shape.noise);
    if (r.shape.sensor_noise > r.shape.measured_noise)  // grasp.shape.depth_error
      std::printf(" (%s at the object's depth; its points scatter %.1f mm)",
                  d.scene.pre.moved_depth_error > cfg.grasp.shape.depth_error
                      ? "the depth error left in the points moved onto their windows' range fits"
                      : "the sensor's depth error",
                  1e3 * r.shape.measured_noise);
    std::printf(", back mirrored about %zu symmetry plane%s (%zu points)", r.shape.planes.size(),
                r.shape.planes.size() == 1 ? "" : "s", r.shape.mirrored_points.size());
    for (const auto& p : r.shape.planes)
      std::printf(", n_L (%.3f, %.3f, %.3f) %.0f %% on the seen surface", p.normal.x(),
                  p.normal.y(), p.normal.z(), 100.0 * p.support);
    std::printf("\n");
  }
  std::printf("sampler %s: %zu candidates, %zu feasible (%.2f %%)\n",
              grasp::sampler_name(r.sampler), r.candidates, r.feasible(),
              r.candidates ? 100.0 * double(r.feasible()) / double(r.candidates) : 0.0);
  std::printf("rejected:");
  for (int k = 1; k < grasp::kRejectKinds; ++k)
    if (r.rejections[k])
      std::printf(" %s %zu", grasp::reject_name(static_cast<grasp::Reject>(k)), r.rejections[k]);
  std::printf("\n");
  if (r.grasps.empty()) {
    print_none(r);
  } else {
    print_best(r.grasps.front(), r.frames, cfg.grasp.score);
    if (frame.name != "camera_optical") {
      const Pose T = frame.from_camera * grasp::camera_from_gripper(r.grasps.front(), r.frames);
      const Eigen::Quaterniond q(T.linear());
      print_vec("  cloud's frame  position ", T.translation(), " m");
      std::printf("  orientation xyzw (%.4f, %.4f, %.4f, %.4f)\n", q.x(), q.y(), q.z(), q.w());
    }
    std::printf(
        "  rank  score  robust   q_fc  mu_req orient  inliers  width m  vehicle r/p/y deg   hold "
        "%%\n");
    for (std::size_t i = 0; i < r.grasps.size(); ++i) {
      const auto& g = r.grasps[i];
      std::printf(
          "  %4zu  %5.3f  %6.3f %6.3f  %6.3f %6.3f  %6.3f  %7.4f  %6.1f %6.1f %6.1f  %6.1f\n",
          i + 1, g.scores.total, g.robustness, g.force_closure, g.friction.mu_required,
          g.scores.orientation, g.scores.inliers, g.width, deg(g.vehicle_rpy.x()),
          deg(g.vehicle_rpy.y()), deg(g.vehicle_rpy.z()), 100 * g.hold_cost);
    }
  }
  std::printf("stage times (ms):");
  for (const auto& st : d.timer.stages()) std::printf(" %s %.1f |", st.name.c_str(), st.ms);
  std::printf(" total %.1f\n", d.timer.total_ms());
}

cv::Mat detection_picture(const Cloud& input, const grasp::Detection& d, const io::Config& cfg,
                          const std::string& name) {
  const auto& r = d.result;
  viz::Picture pic;
  pic.title = std::filesystem::path(name).filename().string() + ": top " +
              std::to_string(r.grasps.size()) + " grasps";
  char line[160];
  std::snprintf(line, sizeof line, "%s sampler: %zu feasible of %zu candidates, object %zu points",
                grasp::sampler_name(r.sampler), r.feasible(), r.candidates, d.object.size());
  pic.legend.push_back(line);
  if (!r.grasps.empty()) {
    std::snprintf(line, sizeof line, "best score %.3f, width %.1f mm",
                  r.grasps.front().scores.total, 1000.0 * r.grasps.front().width);
    pic.legend.push_back(line);
  }
  const auto wires = grasp_wires(r.grasps, r.frames, cfg.grasp.gripper);
  if (r.shape.mirrored_points.empty())
    return viz::draw(input, wires, pic, viz::View{}, d.object.points);
  // The object's back as the grasp engine completed it (mirrored about its symmetry planes),
  // drawn in cyan behind what the camera saw.
  Cloud shown = input;
  make_unorganised(shown);
  if (shown.colors.empty()) shown.colors.assign(shown.size(), Rgb8{160, 160, 160});
  shown.normals.clear(), shown.curvature.clear(), shown.labels.clear();
  const Pose camera_from_level = r.frames.level_from_camera.inverse();
  for (const auto& p : r.shape.mirrored_points) {
    shown.points.push_back((camera_from_level * p.cast<double>()).cast<float>());
    shown.colors.push_back(Rgb8{40, 220, 230});
  }
  make_unorganised(shown);
  pic.legend.push_back("cyan: the object's unseen back, mirrored about its symmetry planes");
  return viz::draw(shown, wires, pic, viz::View{}, d.object.points);
}

}  // namespace uwgrasp::app
