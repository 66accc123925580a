#include "app/judged_picture.hpp"

#include <cmath>

#include "app/simulation.hpp"
#include "uwgrasp/sim/render.hpp"

namespace uwgrasp::app {

Rgb8 outcome_colour(eval::Outcome o) {
  static const Rgb8 c[eval::kOutcomes] = {{40, 190, 60},  {240, 160, 20}, {220, 30, 30}, {150, 150, 150},
                                          {160, 60, 200}, {40, 110, 230}, {40, 200, 210}};
  return c[static_cast<int>(o)];
}

cv::Mat judged_picture(const sim::World& world, const eval::Camera& cam, const grasp::Gripper& g,
                       std::span<const Pose> poses, std::span<const eval::Judgement> judgements,
                       int target, double mu_ref, const viz::Picture& picture, const viz::View& view) {
  sim::RenderConfig rc;
  rc.camera.width = std::uint32_t(cam.intrinsics.width), rc.camera.height = std::uint32_t(cam.intrinsics.height);
  rc.camera.hfov = 2.0 * std::atan(0.5 * cam.intrinsics.width / cam.intrinsics.fx);
  rc.camera.max_range = cam.max_range;
  rc.noise.enabled = false;
  const sim::Frame f = sim::render_rgbd(world, cam.world_from_camera, rc, 1);
  std::vector<Eigen::Vector3f> focus;
  for (std::size_t i = 0; i < f.labels.size(); ++i)
    if (f.labels[i] == sim::kLabelFirstObject + target && f.cloud.points[i].allFinite()) focus.push_back(f.cloud.points[i]);
  const Pose camera_from_world = cam.world_from_camera.inverse();
  // Framed on the object and the grippers' closing regions, so neither is cut off.
  const std::size_t object_points = focus.size();
  for (std::size_t i = 0; i < judgements.size() && object_points > 0; ++i)
    focus.insert(focus.end(), object_points / (judgements.size() + 1) + 1,
                 (camera_from_world * poses[i].translation()).cast<float>());
  std::vector<viz::Wire> wires;
  for (std::size_t i = judgements.size(); i-- > 0;) {
    const eval::Judgement& j = judgements[i];
    viz::Wire w = gripper_wire(camera_from_world * poses[i], g, false);
    w.colour = outcome_colour(eval::outcome(j, mu_ref));
    w.thickness = i == 0 ? 4 : 2;
    w.value = double(judgements.size() - i);
    if (j.verdict == eval::Verdict::closes)
      for (const Eigen::Vector3d& c : j.contacts)
        for (int a = 0; a < 3; ++a) {
          const Eigen::Vector3f p = (camera_from_world * c).cast<float>();
          const Eigen::Vector3f d = 0.006f * Eigen::Vector3f::Unit(a);
          w.segments.push_back({p - d, p + d});
        }
    wires.push_back(std::move(w));
  }
  viz::Picture pic = picture;
  for (int k = 0; k < eval::kOutcomes; ++k)
    pic.key.emplace_back(eval::outcome_name(eval::Outcome(k)), outcome_colour(eval::Outcome(k)));
  return viz::draw(f.cloud, wires, pic, view, focus);
}

}  // namespace uwgrasp::app
