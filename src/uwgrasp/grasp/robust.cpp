#include "uwgrasp/grasp/robust.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::grasp {

namespace {
// A solid part below the seafloor (any corner past the plane) or wholly inside the model.
bool blocked(const ModelView& m, const Candidate& c) {
  for (const Box& b : m.gripper.solids) {
    if (m.shape.occupied(c.rotation * b.centre() + c.position)) return true;
    if (!m.floor) continue;
    for (int k = 0; k < 8; ++k)
      if (m.floor->head<3>().dot(c.rotation * b.corner(k) + c.position) + (*m.floor)[3] < 0.0f) return true;
  }
  return false;
}
}  // namespace

ContactPrediction predict(const ModelView& m, const Candidate& c) {
  thread_local std::vector<std::uint32_t> idx;  // each thread's, reused (closing_indices clears it)
  closing_indices(m.bvh, m.gripper, c, idx);
  ContactPrediction p = predict_contacts(m.points, m.normals, idx, c, m.band, m.radius, m.measured);
  if (m.core_bvh == nullptr || !p.valid) return p;
  idx.clear();
  closing_indices(*m.core_bvh, m.gripper, c, idx);
  const ContactPrediction least =
      predict_contacts(m.core_points, m.core_normals, idx, c, m.band, m.radius, m.measured);
  p.valid = least.valid;
  if (!least.valid) p.mu = std::numeric_limits<float>::infinity();
  else if (m.core_friction) p.mu = std::max(p.mu, least.mu);
  return p;
}

bool holds_on_model(const ModelView& m, const Candidate& c, double mu) {
  return holds_on_model(m, Checker(m.bvh, m.gripper), c, mu);
}

bool holds_on_model(const ModelView& m, const Checker& check, const Candidate& c, double mu) {
  if (!check(c).feasible() || blocked(m, c)) return false;
  if (m.scene != nullptr && m.scene->gripper_at_pose(c) != Reject::none) return false;
  const ContactPrediction p = predict(m, c);
  return p.valid && p.mu <= mu;
}

Candidate perturb(const Candidate& c, const RobustConfig& cfg, std::uint64_t seed,
                  std::uint32_t candidate, std::uint32_t k) {
  Rng rng(seed ^ 0x3C6EF372FE94F82BULL, (std::uint64_t(candidate) << 20) ^ k);
  Eigen::Vector3d d, w;
  for (int i = 0; i < 3; ++i) d[i] = rng.normal(0.0, cfg.sigma_position);
  for (int i = 0; i < 3; ++i) w[i] = rng.normal(0.0, cfg.sigma_angle);
  Candidate out = c;
  out.position += d.cast<float>();
  if (w.norm() > 0.0)
    out.rotation = c.rotation * Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix().cast<float>();
  return out;
}

std::vector<float> robustness(const ModelView& m, std::span<const Candidate> candidates,
                              std::span<const std::uint32_t> which, const RobustConfig& cfg,
                              std::uint64_t seed, std::uint32_t first, std::uint32_t samples) {
  if (samples == 0) samples = cfg.samples;
  std::vector<float> out(which.size(), 0.0f);
  if (samples == 0) return out;
  std::vector<char> held(which.size() * samples, 0);
  // One checker for every perturbed pose: one per pose was ~1,500 allocations a frame.
  const Checker check(m.bvh, m.gripper);
  tbb::parallel_for(std::size_t(0), held.size(), [&](std::size_t t) {
    const std::uint32_t i = which[t / samples], k = first + std::uint32_t(t % samples);
    held[t] = holds_on_model(m, check, perturb(candidates[i], cfg, seed, i, k), cfg.mu);
  });
  for (std::size_t j = 0; j < which.size(); ++j)
    out[j] = float(std::count(held.begin() + std::ptrdiff_t(j * samples),
                              held.begin() + std::ptrdiff_t((j + 1) * samples), 1)) / float(samples);
  return out;
}

}  // namespace uwgrasp::grasp
