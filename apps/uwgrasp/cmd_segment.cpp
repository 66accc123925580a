// uwgrasp segment CLOUD [--out-dir DIR] [--png FILE]: preprocessing + segmentation (thesis ch. 4).
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/common.hpp"
#include "app/frame.hpp"
#include "commands.hpp"
#include "app/simulation.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/pcd.hpp"
#include "uwgrasp/segment/pipeline.hpp"

namespace uwgrasp::app {

namespace {
struct SegmentOptions {
  CommonOptions common;
  FrameOptions frame;
  std::string cloud;
  std::string out_dir;
  std::string png;
};

void print_table(const std::string& name, const segment::Scene& s, long selected,
                 const std::string& color) {
  const auto& c = s.pre.counts;
  std::printf("%s: %zu points in, %zu finite, %zu in range, %zu after the voxel grid\n",
              name.c_str(), c.input, c.finite, c.in_range, c.voxels);
  if (s.pre.plane.found) {
    const auto& m = s.pre.plane.coefficients;
    std::printf("plane: %zu inliers removed, n = (%.4f, %.4f, %.4f), d = %.4f m\n", c.plane, m[0],
                m[1], m[2], m[3]);
    if (s.pre.noise.found)
      std::printf("depth noise on the plane: sigma(r) = %.2f mm + %.2f mm/m^2 r^2 (%.1f mm at 1 m, %.1f mm at 3 m)\n",
                  1e3 * s.pre.noise.sigma0, 1e3 * s.pre.noise.sigma_k, 1e3 * s.pre.noise.at(1.0),
                  1e3 * s.pre.noise.at(3.0));
  } else {
    std::printf("plane: none found\n");
  }
  if (s.pre.organised) std::printf("normals: %s\n", cloud::normals_summary(s.pre).c_str());
  std::printf("%zu points after outlier removal, segmented into %zu segments\n\n", c.output,
              s.info.size());
  std::printf("  seg   points   centroid x      y      z (m)   mean r   g   b   %s\n",
              color.c_str());
  for (std::size_t i = 0; i < s.info.size(); ++i) {
    const auto& si = s.info[i];
    std::printf("%c %3zu %8zu   %8.3f %6.3f %6.3f       %3d %3d %3d   %.2f\n",
                static_cast<long>(i) == selected ? '*' : ' ', i, si.points, si.centroid.x(),
                si.centroid.y(), si.centroid.z(), si.mean_color.r, si.mean_color.g,
                si.mean_color.b, si.intensity);
  }
  std::printf("\nstage times (ms):");
  for (const auto& st : s.timer.stages()) std::printf(" %s %.1f |", st.name.c_str(), st.ms);
  std::printf(" total %.1f\n", s.timer.total_ms());
}

// The input cloud with a label per point: 0 = no segment, k + 1 = segment k.
Cloud labelled_cloud(const Cloud& input, const segment::Scene& s) {
  Cloud out = input;
  const auto lab = segment::input_labels(s);
  out.labels.resize(input.size());
  for (std::size_t i = 0; i < lab.size(); ++i) out.labels[i] = static_cast<std::uint32_t>(lab[i] + 1);
  return out;
}

// A cloud of the pipeline (camera frame) back in the input's frame, with the camera pose as its
// VIEWPOINT, so the written clouds overlay the input.
Cloud in_input_frame(Cloud c, const io::OutputFrame& f) {
  c.viewpoint.setZero(), c.orientation.setIdentity();
  return f.from_camera.isApprox(Pose::Identity()) ? c : transformed(c, f.from_camera);
}

void write_outputs(const SegmentOptions& o, const Cloud& input, const segment::Scene& s,
                   const io::OutputFrame& frame) {
  namespace fs = std::filesystem;
  make_output_dir(o.out_dir);
  std::error_code ec;
  std::vector<std::string> written;
  try {
    for (std::size_t i = 0; i < s.segmentation.segments.size(); ++i) {
      char name[48];
      std::snprintf(name, sizeof name, "segment_%03zu.pcd", i);
      written.push_back((fs::path(o.out_dir) / name).string());
      io::save_cloud(written.back(),
                     in_input_frame(select(s.pre.cloud, s.segmentation.segments[i]), frame));
    }
    written.push_back((fs::path(o.out_dir) / "labelled.pcd").string());
    io::save_cloud(written.back(), in_input_frame(labelled_cloud(input, s), frame));
  } catch (...) {
    for (const auto& w : written) fs::remove(w, ec);  // no partial output
    throw;
  }
  std::printf("wrote %zu segment clouds and labelled.pcd to %s\n",
              s.segmentation.segments.size(), o.out_dir.c_str());
}
}  // namespace

void add_segment_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners) {
  auto* cmd = app.add_subcommand(
      "segment", "Preprocess and segment a cloud; print the segments, optionally write them");
  auto o = std::make_shared<SegmentOptions>();
  cmd->add_option("CLOUD", o->cloud, ".pcd or .ply cloud, in the camera optical frame unless its "
                  "VIEWPOINT or --camera-pose gives the camera pose")->required();
  add_frame_options(*cmd, o->frame);
  cmd->add_option("--out-dir", o->out_dir,
                  "Write segment_NNN.pcd per segment and labelled.pcd (label 0: none, k+1: "
                  "segment k) here");
  cmd->add_option("--png", o->png, "Draw the segments, one colour each (grey: no segment), here");
  add_common(*cmd, o->common);
  runners.emplace_back(cmd, [o] {
    const Session session = open_session(o->common);
    const io::Config& cfg = session.config;
    progress("uwgrasp segment: loading " + o->cloud);
    const CameraCloud in = to_camera_frame(io::load_cloud(o->cloud), o->frame, o->cloud);
    const Cloud& input = in.cloud;
    progress("uwgrasp segment: " + std::to_string(input.size()) + " points, segmenting");
    const segment::Scene scene = about_input(
        o->cloud, [&] { return segment::segment_scene(input, cfg.preprocess, cfg.segment, cfg.seed); });
    long selected = -1;
    if (!scene.info.empty() && (input.has_colors() || cfg.segment.object.by != segment::ObjectBy::color)) {
      try {
        selected = static_cast<long>(segment::select_object(scene.info, cfg.segment.object));
      } catch (const Error&) {
        selected = -1;  // the table still lists every segment
      }
    }
    std::printf("path: %s\nframe: %s\n", cloud::path_summary(input, cfg.preprocess).c_str(),
                in.summary.c_str());
    print_table(o->cloud, scene, selected, cfg.segment.object.color);
    if (!o->out_dir.empty()) write_outputs(*o, input, scene, in.frame);
    if (!o->png.empty()) {
      viz::Picture pic;
      pic.title = std::filesystem::path(o->cloud).filename().string() + ": " +
                  std::to_string(scene.info.size()) + " segments";
      pic.colour_by_label = true;
      if (selected >= 0) pic.legend.push_back("object of interest: segment " + std::to_string(selected));
      write_png(o->png, viz::draw(labelled_cloud(input, scene), {}, pic));
      std::printf("wrote %s\n", o->png.c_str());
    }
    return 0;
  });
}

}  // namespace uwgrasp::app
