#include "uwgrasp/eval/exists.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <atomic>
#include <cmath>
#include <numbers>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::eval {

namespace {
using V3 = Eigen::Vector3d;

// The gripper frames tried for one antipodal pair: approaches turned about the closing axis,
// the contacts at the pads' centre and towards either end (exists.hpp).
std::vector<Pose> poses_for(const V3& near, const V3& y, double width, const grasp::Gripper& g,
                            const ExistenceConfig& cfg) {
  std::vector<Pose> out;
  const V3 start = std::abs(y.z()) < 0.9 ? V3::UnitZ() : V3::UnitX();
  const V3 x0 = (start - start.dot(y) * y).normalized();
  const double half = 0.5 * g.config.finger_length;
  for (std::uint32_t a = 0; a < cfg.approaches; ++a) {
    const V3 x = Eigen::AngleAxisd(2.0 * std::numbers::pi * a / cfg.approaches, y) * x0;
    for (std::uint32_t d = 0; d < cfg.depths; ++d) {
      const double along = cfg.depths > 1 ? 0.95 * half * (-1.0 + 2.0 * double(d) / double(cfg.depths - 1)) : 0.0;
      Pose T = Pose::Identity();
      T.linear().col(0) = x, T.linear().col(1) = y, T.linear().col(2) = x.cross(y);
      T.translation() = near + 0.5 * width * y - along * x;
      out.push_back(T);
    }
  }
  return out;
}
}  // namespace

Existence find_any_grasp(const sim::World& world, const Camera& camera, const grasp::Gripper& gripper,
                         int target, const ExistenceConfig& cfg) {
  if (target < 0 || std::size_t(target) >= world.scene().objects.size())
    throw Error("grasp search: target object " + std::to_string(target) + " is not in the scene");
  const std::vector<sim::SurfaceSample> samples = sim::sample_object_surface(world, target, cfg.points, cfg.seed);
  const double usable = grasp::max_grasp_width(gripper);
  const std::size_t per = std::size_t(cfg.approaches) * cfg.depths;
  std::atomic<std::size_t> first{samples.size() * per};
  tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t i) {
    if (i * per >= first.load()) return;  // a lower index already holds
    const V3 y = -samples[i].normal;
    const sim::RayHit exit = sim::first_hit(world, {samples[i].point + 1e-5 * y, y, usable + 0.01});
    if (!exit.hit || exit.object != target || exit.t > usable) return;
    const std::vector<Pose> poses = poses_for(samples[i].point, y, exit.t, gripper, cfg);
    for (std::size_t k = 0; k < poses.size(); ++k)
      if (judge(world, camera, gripper, poses[k], target).holds(cfg.mu)) {
        std::size_t cur = first.load();
        while (i * per + k < cur && !first.compare_exchange_weak(cur, i * per + k)) {
        }
        return;
      }
  });
  Existence e;
  const std::size_t f = first.load();
  e.exists = f < samples.size() * per;
  e.tried = e.exists ? f + 1 : samples.size() * per;
  if (e.exists) {
    const std::size_t i = f / per;
    const V3 y = -samples[i].normal;
    const sim::RayHit exit = sim::first_hit(world, {samples[i].point + 1e-5 * y, y, usable + 0.01});
    e.example = poses_for(samples[i].point, y, exit.t, gripper, cfg)[f % per];
  }
  return e;
}

}  // namespace uwgrasp::eval
