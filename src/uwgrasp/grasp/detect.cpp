// The whole pipeline from a cloud (detector.hpp): segment the scene, pick the object of
// interest as a whole, gather what surrounds it, and find grasps on it (find_grasps, in
// detector.cpp).
#include <algorithm>
#include <string>
#include <vector>

#include "uwgrasp/cloud/color.hpp"
#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/segment/objects.hpp"

namespace uwgrasp::grasp {

namespace {
// The cloud whose colours select the object: the processed one, or, when selecting by colour
// finds no object of it there and the water's fallback is on (restoration off), a copy with the
// colours restored (cloud/color.hpp: the restoration is per point, as in preprocessing).
const Cloud& colours_for_selection(const Cloud& c, const segment::Objects& objects,
                                   const segment::ObjectConfig& cfg,
                                   const cloud::WaterColorConfig* fallback, Cloud& restored) {
  if (cfg.by != segment::ObjectBy::color || fallback == nullptr || !c.has_colors() ||
      objects.points.empty() || segment::has_colour_object(c, objects, cfg))
    return c;
  restored = c;
  cloud::restore_colors(restored, *fallback);
  return restored;
}

// The whole object the criterion picks among the processed cloud's connected objects, as
// ascending indices into the processed cloud; `selected` becomes its largest segment.
// `restored_colours`: whether colours_for_selection restored them.
std::vector<std::uint32_t> whole_object(const segment::Scene& scene,
                                        const segment::ObjectConfig& cfg, std::size_t& selected,
                                        const cloud::WaterColorConfig* fallback,
                                        bool& restored_colours) {
  const Cloud& c = scene.pre.cloud;
  cloud::Neighbours own;
  const cloud::Neighbours* nb = &scene.pre.neighbours;
  if (nb->count.size() != c.size()) {  // radius-mode normals keep no lists: search them here
    const cloud::KdTree tree(c.points);
    own = cloud::knn_all(tree, c.points, 16);
    nb = &own;
  }
  const float gap = cfg.gap > 0.0f ? cfg.gap : segment::connection_gap(*nb);
  const segment::Objects objects = segment::connected_objects(c, *nb, gap, 10);
  Cloud restored;
  const Cloud& coloured = colours_for_selection(c, objects, cfg, fallback, restored);
  restored_colours = &coloured != &c;
  std::size_t k = 0;
  try {
    k = segment::select_whole_object(coloured, objects, scene.segmentation, cfg);
  } catch (const Error& e) {
    if (!restored_colours) throw;
    throw Error(std::string(e.what()) + "; restored with preprocess.water's coefficients the " +
                "colours did not show it either (set the water's own)");
  }
  std::vector<std::uint32_t> points;
  for (const std::size_t part : segment::gather_parts(coloured, objects, k, cfg, cfg.part_reach))
    points.insert(points.end(), objects.points[part].begin(), objects.points[part].end());
  std::sort(points.begin(), points.end());
  std::vector<std::size_t> votes(scene.segmentation.segments.size(), 0);
  for (const auto i : objects.points[k])
    if (scene.segmentation.label[i] >= 0) ++votes[std::size_t(scene.segmentation.label[i])];
  selected = std::size_t(std::max_element(votes.begin(), votes.end()) - votes.begin());
  return points;
}

// The object's points as ascending indices into the processed cloud (object_points).
std::vector<std::uint32_t> object_indices(const segment::Scene& scene,
                                          const segment::ObjectConfig& cfg, std::size_t& selected,
                                          const cloud::WaterColorConfig* fallback = nullptr,
                                          bool* restored_colours = nullptr) {
  if (scene.info.empty())
    throw Error("segmentation found no segment to grasp in the " +
                std::to_string(scene.pre.cloud.size()) +
                " points left after preprocessing (a segment needs segment.region.min_size points)");
  bool ignored = false;
  if (cfg.whole)
    return whole_object(scene, cfg, selected, fallback,
                        restored_colours ? *restored_colours : ignored);
  selected = segment::select_object(scene.info, cfg);
  std::vector<std::uint32_t> points;
  for (const std::size_t s : segment::object_segments(scene.info, selected, cfg)) {
    const auto& idx = scene.segmentation.segments[s];
    points.insert(points.end(), idx.begin(), idx.end());
  }
  std::sort(points.begin(), points.end());
  return points;
}
}  // namespace

Cloud object_points(const segment::Scene& scene, const segment::ObjectConfig& cfg,
                    std::size_t& selected) {
  return select(scene.pre.cloud, object_indices(scene, cfg, selected));
}

Surroundings surroundings(const segment::Scene& scene, std::vector<Eigen::Vector3f>& points,
                          const Cloud* input) {
  points = scene.pre.cloud.points;
  const auto& out_of = scene.pre.output_of_input;
  if (input != nullptr && out_of.size() == input->size()) {
    float far = 0.0f;  // as far as the processed cloud reaches (the range crop stays cropped)
    for (const auto& p : scene.pre.cloud.points) far = std::max(far, p.squaredNorm());
    for (std::size_t i = 0; i < input->size(); ++i)
      if (out_of[i] < 0 && !scene.pre.plane_of_input[i] && is_finite(input->points[i]) &&
          input->points[i].squaredNorm() <= far)
        points.push_back(input->points[i]);
  }
  return {points, scene.pre.plane.found, scene.pre.plane.coefficients};
}

void detect(const Cloud& input, const cloud::PreprocessConfig& pre,
            const segment::SegmentConfig& seg, const GraspConfig& cfg, std::uint64_t seed,
            Detection& d, segment::Workspace& ws) {
  d.restored_colours = false;  // whole_object sets it; the other selections leave it
  d.segment = 0;
  d.result = ObjectGrasps{};
  segment::segment_scene(input, pre, seg, seed, d.scene, ws);
  d.timer = d.scene.timer;
  d.timer.start("select");
  const bool fallback = pre.water.fallback && !pre.water.enabled;
  const std::vector<std::uint32_t> object = object_indices(
      d.scene, seg.object, d.segment, fallback ? &pre.water : nullptr, &d.restored_colours);
  select(d.scene.pre.cloud, object, d.object);
  d.timer.stop();
  const double leaf = pre.voxel.enabled ? pre.voxel.leaf : 0.0;
  Surroundings around = surroundings(d.scene, d.obstacles, &input);
  // The rest of the processed scene rests on the seafloor (columns.hpp); not the points outlier
  // removal dropped (after the processed ones in d.obstacles): stray pixels stand for no column.
  d.rests.assign(d.obstacles.size(), 0);
  std::fill_n(d.rests.begin(), d.scene.pre.cloud.size(), char(1));
  for (const std::uint32_t i : object) d.rests[i] = 0;
  around.rests = d.rests;
  d.floor_attitude.reset();
  if (levels_from_floor(cfg.frames) && d.scene.pre.plane.found)
    d.floor_attitude = attitude_from_floor(d.scene.pre.plane.coefficients, cfg.frames);
  // Points moved onto their windows' range fits scatter far less than they err: the object's model
  // takes the error left in them as its noise floor (cloud::Preprocessed::moved_depth_error).
  const float moved = float(d.scene.pre.moved_depth_error);
  if (!d.floor_attitude && !(moved > cfg.shape.depth_error)) {
    d.result = find_grasps(d.object, cfg, leaf, seed, d.timer, &around);
    return;
  }
  GraspConfig adapted = cfg;
  adapted.shape.depth_error = std::max(cfg.shape.depth_error, moved);
  if (d.floor_attitude) {
    adapted.frames.capture_roll = d.floor_attitude->roll;
    adapted.frames.capture_pitch = d.floor_attitude->pitch;
  }
  d.result = find_grasps(d.object, adapted, leaf, seed, d.timer, &around);
}

Detection detect(const Cloud& input, const cloud::PreprocessConfig& pre,
                 const segment::SegmentConfig& seg, const GraspConfig& cfg, std::uint64_t seed) {
  Detection d;
  segment::Workspace ws;
  detect(input, pre, seg, cfg, seed, d, ws);
  return d;
}

Pose camera_from_gripper(const Grasp& g, const Frames& f) {
  return f.level_from_camera.inverse() * g.level_from_gripper;
}

}  // namespace uwgrasp::grasp
