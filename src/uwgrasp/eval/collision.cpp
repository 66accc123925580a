// Step 1 of judging: the gripper's solid parts against the true objects and the seafloor.
#include <algorithm>
#include <cmath>

#include "uwgrasp/eval/steps.hpp"
#include "uwgrasp/sim/scene.hpp"

namespace uwgrasp::eval::detail {

namespace {
using V3 = Eigen::Vector3d;

// The part's box in W, shrunk by the tolerance on every side (a penetration up to it is slack).
sim::OrientedBox part_box(const grasp::Box& b, const Pose& T, double tolerance) {
  sim::OrientedBox box;
  box.centre = T * b.centre().cast<double>();
  box.rotation = T.linear();
  box.half = (b.half().cast<double>().array() - tolerance).max(0.0).matrix();
  return box;
}

// The deepest corner of the box below the seafloor (W: z up, the floor is z = 0 within its
// square), or false when the box stays above it.
bool below_floor(const sim::Scene& scene, const sim::OrientedBox& box, V3& deepest) {
  if (!scene.seafloor.enabled) return false;
  bool found = false;
  for (int k = 0; k < 8; ++k) {
    const V3 q((k & 1) ? box.half.x() : -box.half.x(), (k & 2) ? box.half.y() : -box.half.y(),
               (k & 4) ? box.half.z() : -box.half.z());
    const V3 p = box.centre + box.rotation * q;
    const double h = 0.5 * scene.seafloor.size;
    if (p.z() < 0.0 && std::abs(p.x()) <= h && std::abs(p.y()) <= h && (!found || p.z() < deepest.z()))
      deepest = p, found = true;
  }
  return found;
}
}  // namespace

bool visible(const sim::World& world, const Camera& camera, const V3& p, double tolerance) {
  const V3 c = camera.world_from_camera.inverse() * p;
  if (!(c.z() > 0.0)) return false;
  const Eigen::Vector2d px = camera.intrinsics.project(c);
  const auto& k = camera.intrinsics;
  if (px.x() < -0.5 || px.y() < -0.5 || px.x() > k.width - 0.5 || px.y() > k.height - 0.5) return false;
  if (c.z() > camera.max_range) return false;
  const V3 o = camera.world_from_camera.translation();
  const double d = (p - o).norm();
  const sim::RayHit h = sim::first_hit(world, {o, (p - o) / d, d + tolerance});
  return !h.hit || h.t >= d - tolerance;
}

bool collides(const sim::World& world, const Camera& camera, const grasp::Gripper& gripper,
              const Pose& T, const JudgeConfig& cfg, Judgement& j) {
  for (int part = 0; part < grasp::kParts; ++part) {
    const sim::OrientedBox box = part_box(gripper.solids[std::size_t(part)], T, cfg.tolerance);
    const std::vector<sim::BoxContact> touched = sim::surfaces_in_box(world, box);
    if (!touched.empty()) {
      j = Judgement{Verdict::collision, part, touched.front().object};
      // Seen if any crossed piece of that object's surface was in the camera's view.
      for (const sim::BoxContact& c : touched)
        if (c.object == j.object && visible(world, camera, c.witness, cfg.visibility_tolerance)) {
          j.visible = true;
          break;
        }
      return true;
    }
    // No surface crosses the box: it is wholly inside an object or wholly outside every one.
    if (const std::vector<int> in = sim::inside_objects(world, box.centre); !in.empty()) {
      j = Judgement{Verdict::collision, part, in.front()};
      j.inside = true;
      return true;
    }
    V3 deepest = V3::Zero();
    if (below_floor(world.scene(), box, deepest)) {
      j = Judgement{Verdict::collision, part, sim::kSeafloorObject};
      j.visible = visible(world, camera, V3(deepest.x(), deepest.y(), 0.0), cfg.visibility_tolerance);
      return true;
    }
  }
  return false;
}

}  // namespace uwgrasp::eval::detail
