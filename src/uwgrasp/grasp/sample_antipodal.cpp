// The antipodal sampler (samplers.hpp) on the object's model (shape.hpp).
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/grasp/samplers.hpp"
#include "uwgrasp/grasp/shape.hpp"

namespace uwgrasp::grasp {

namespace {
constexpr std::uint64_t kAntipodal = 5ULL << 40;
using V3 = Eigen::Vector3f;

// How far the model reaches from p along u (unit) before `gap` of free space, up to `limit`.
float extent_along(const ObjectShape& shape, const V3& p, const V3& u, float limit, float gap) {
  const float step = 0.5f * shape.voxel;
  float last = 0.0f;
  for (float t = step; t <= limit + gap; t += step) {
    if (shape.occupied(p + t * u)) last = t;
    else if (t - last > gap) break;
  }
  return last;
}

// How far the gripper must back off along -x from `centre` so that its palm face (at
// -palm_offset, `half_width` across y, `half_height` across z) clears the model by a voxel and
// a half (the grid's own quantisation): the furthest the model reaches towards it over a 5 x 3
// grid of lines through the palm's face.
float back_off(const ObjectShape& shape, const V3& centre, const V3& x, const V3& y, float palm_offset,
               float half_width, float half_height) {
  const V3 z = x.cross(y);
  float reach = -std::numeric_limits<float>::max();
  for (const float a : {-1.0f, -0.5f, 0.0f, 0.5f, 1.0f})
    for (const float b : {-1.0f, 0.0f, 1.0f})
      for (float t = 0.0f; t <= 2.0f * palm_offset; t += 0.5f * shape.voxel)
        if (shape.occupied(centre + a * half_width * y + b * half_height * z - t * x)) reach = std::max(reach, t);
  return std::max(0.0f, reach + 1.5f * shape.voxel - palm_offset);
}

V3 tilted(const V3& axis, Rng& rng, double sigma) {
  const Eigen::Vector3d w(rng.normal(0.0, sigma), rng.normal(0.0, sigma), rng.normal(0.0, sigma));
  const Eigen::Vector3d a = axis.cast<double>();
  const Eigen::Vector3d w_perp = w - w.dot(a) * a;  // a turn about an axis across `axis`
  if (w_perp.norm() < 1e-12) return axis;
  return (Eigen::AngleAxisd(w_perp.norm(), w_perp.normalized()) * a).cast<float>().normalized();
}
}  // namespace

std::vector<Candidate> sample_antipodal(std::span<const Eigen::Vector3f> points,
                                        std::span<const Eigen::Vector3f> normals,
                                        const ObjectShape& shape, const SamplerConfig& cfg,
                                        const Eigen::Matrix3d& R_BG, float max_width,
                                        float palm_offset, float palm_half_width,
                                        float palm_half_height, std::uint64_t seed,
                                        std::uint32_t count, std::uint32_t first) {
  if (points.empty()) throw Error("antipodal sampler: the object cloud is empty");
  if (normals.size() != points.size()) throw Error("antipodal sampler: the object has no normals");
  if (shape.empty()) throw Error("antipodal sampler: needs the object's shape (grasp.shape.enabled)");
  std::vector<Candidate> out(count);
  const float gap = 2.0f * shape.voxel;
  // The points worth drawing: a usable normal, and the model no wider than the gripper's usable
  // aperture along it (on an object mostly wider than the gripper, the few graspable places).
  std::vector<char> ok(points.size(), 0);
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t j) {
    ok[j] = normals[j].norm() > 0.5f && extent_along(shape, points[j], -normals[j].normalized(), max_width, gap) <= max_width;
  });
  std::vector<std::uint32_t> eligible;
  for (std::uint32_t j = 0; j < points.size(); ++j)
    if (ok[j]) eligible.push_back(j);
  if (eligible.empty()) {
    eligible.resize(points.size());
    std::iota(eligible.begin(), eligible.end(), 0u);
  }
  tbb::parallel_for(std::uint32_t(0), count, [&](std::uint32_t k) {
    Rng rng(seed, kAntipodal + first + k);
    Candidate& c = out[k];
    for (int attempt = 0; attempt < 8; ++attempt) {
      const std::uint32_t j = eligible[rng.below(eligible.size())];
      const V3 n = normals[j];
      if (!(n.norm() > 0.5f)) continue;
      const V3 y = tilted(-n.normalized(), rng, cfg.sigma_tilt);  // from the near pad into the object
      const float width = extent_along(shape, points[j], y, max_width, gap);
      // The gripper's approach at a drawn vehicle attitude, turned across the closing axis.
      const Eigen::Vector3d rpy(rng.normal(0.0, cfg.sigma_theta.x()), rng.normal(0.0, cfg.sigma_theta.y()),
                                rng.normal(0.0, cfg.sigma_theta.z()));
      const V3 a = (quat_from_rpy(rpy).toRotationMatrix() * R_BG).col(0).cast<float>();
      V3 x = a - a.dot(y) * y;
      // Closing along the drawn approach leaves the approach's small remainder across it: the
      // turns below make any of its directions usable.
      if (x.norm() < 1e-4f) continue;
      x.normalize();
      // An approach climbing more than 20 degrees comes from below the object: mirrored, it
      // comes from above, where a vehicle over the seafloor can be (L's z is down).
      if (x.z() < -0.34f) x = -x;
      const V3 mid = points[j] + 0.5f * width * y;
      // Of the drawn approach and its turns about the closing axis by 60, 120 and 180 degrees
      // (nearest first, none from below), the first whose palm clears the model with the
      // contacts still between the pads; else the one that backs off least.
      float best_off = std::numeric_limits<float>::max();
      V3 best_x = x;
      for (int turn = 0; turn < 6 && best_off > 0.5f * palm_offset; ++turn) {
        const int side = (turn + 1) / 2 * (turn % 2 ? 1 : -1);  // 0, +1, -1, +2, -2, +3 sixths
        const V3 xt = Eigen::AngleAxisf(float(side) * float(std::numbers::pi) / 3.0f, y) * x;
        if (xt.z() < -0.34f) continue;
        const float off = back_off(shape, mid, xt, y, palm_offset, palm_half_width, palm_half_height);
        if (off < best_off) best_off = off, best_x = xt;
      }
      x = best_x;
      c.position = mid - best_off * x;
      c.rotation.col(0) = x, c.rotation.col(1) = y, c.rotation.col(2) = x.cross(y);
      c.source = static_cast<std::int32_t>(j);
      if (width <= max_width) break;
    }
  });
  return out;
}

}  // namespace uwgrasp::grasp
