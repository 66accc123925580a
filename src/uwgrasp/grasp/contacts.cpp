#include "uwgrasp/grasp/contacts.hpp"

#include <algorithm>
#include <vector>

#include "uwgrasp/grasp/metrics.hpp"

namespace uwgrasp::grasp {

namespace {
using V3 = Eigen::Vector3f;

struct Scratch {
  std::vector<V3> local, nrm;
  std::vector<char> from_camera;
  std::vector<std::uint32_t> near;
};

// The side's first point along y (sign +1: the left pad, lowest y) among `idx`, and the mean
// position and normal of the points within `band` of it.
bool first_along(std::span<const V3> local, std::span<const V3> normals_g, std::span<const std::uint32_t> idx,
                 std::span<const char> measured, float sign, float band, V3& at, V3& normal, bool& seen) {
  if (idx.empty()) return false;
  float extreme = std::numeric_limits<float>::max();
  for (const auto k : idx) extreme = std::min(extreme, sign * local[k].y());
  V3 sum = V3::Zero(), n = V3::Zero();
  int count = 0, from_camera = 0;
  for (const auto k : idx)
    if (sign * local[k].y() <= extreme + band) sum += local[k], n += normals_g[k], ++count, from_camera += measured[k];
  at = sum / float(count);
  seen = 2 * from_camera >= count;
  if (n.norm() < 1e-6f) return false;
  normal = n.normalized();
  return true;
}
}  // namespace

ContactPrediction predict_contacts(std::span<const Eigen::Vector3f> points,
                                   std::span<const Eigen::Vector3f> normals,
                                   std::span<const std::uint32_t> closing, const Candidate& c,
                                   float band, float radius, std::size_t measured) {
  ContactPrediction p;
  if (closing.size() < 2) return p;
  // Gripper-frame copies of the region's points and normals (indexed 0..n-1), in buffers each
  // thread keeps: the robustness and score stages predict ~10^4 closings a frame, and their
  // allocations were half of a warm frame's calls to the allocator.
  thread_local Scratch scratch;
  auto& [local, nrm, from_camera, near] = scratch;
  local.resize(closing.size()), nrm.resize(closing.size()), from_camera.resize(closing.size());
  const Eigen::Matrix3f Rt = c.rotation.transpose();
  for (std::size_t i = 0; i < closing.size(); ++i) {
    local[i] = Rt * (points[closing[i]] - c.position);
    nrm[i] = Rt * normals[closing[i]];
    from_camera[i] = closing[i] < measured;
  }
  float lo = std::numeric_limits<float>::max(), hi = -lo;
  for (const V3& q : local) lo = std::min(lo, q.y()), hi = std::max(hi, q.y());
  p.width = hi - lo;
  // The contact patches' centres on the pads, and the line of action through their middle.
  Eigen::Vector2f patch[2] = {Eigen::Vector2f::Zero(), Eigen::Vector2f::Zero()};
  int count[2] = {0, 0};
  for (const V3& q : local) {
    if (q.y() <= lo + band) patch[0] += Eigen::Vector2f(q.x(), q.z()), ++count[0];
    if (q.y() >= hi - band) patch[1] += Eigen::Vector2f(q.x(), q.z()), ++count[1];
  }
  p.line = 0.5f * (patch[0] / float(count[0]) + patch[1] / float(count[1]));
  near.clear();
  for (float r = radius; near.size() < 2 && r <= 8.0f * radius; r *= 2.0f) {
    near.clear();
    for (std::uint32_t i = 0; i < local.size(); ++i)
      if ((Eigen::Vector2f(local[i].x(), local[i].z()) - p.line).squaredNorm() <= r * r) near.push_back(i);
  }
  V3 at[2], n[2];
  if (!first_along(local, nrm, near, from_camera, 1.0f, band, at[0], n[0], p.seen[0]) ||
      !first_along(local, nrm, near, from_camera, -1.0f, band, at[1], n[1], p.seen[1]))
    return p;
  for (int s = 0; s < 2; ++s) p.contact[s] = c.rotation * at[s] + c.position, p.normal[s] = c.rotation * n[s];
  p.mu = float(force_closure_mu(at[0].cast<double>(), n[0].cast<double>(), at[1].cast<double>(),
                                n[1].cast<double>(), Eigen::Vector3d::UnitY()));
  p.valid = true;
  return p;
}

}  // namespace uwgrasp::grasp
