#include "uwgrasp/grasp/samplers.hpp"

#include <tbb/parallel_for.h>

#include <cmath>
#include <numeric>
#include <string>

#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::grasp {

namespace {
// Stream families, so the samplers never share random numbers.
constexpr std::uint64_t kPick = 1ULL << 40, kUniform = 2ULL << 40, kNormal = 3ULL << 40,
                        kSurface = 4ULL << 40;

Eigen::Vector3d normal3(Rng& rng, const Eigen::Vector3d& sigma) {
  const double a = rng.normal(), b = rng.normal(), c = rng.normal();
  return {sigma.x() * a, sigma.y() * b, sigma.z() * c};
}

// Gripper orientation for a sampled vehicle attitude: R_LG = R(rpy) * R_BG.
Eigen::Matrix3f gripper_rotation(const Eigen::Vector3d& rpy, const Eigen::Matrix3d& R_BG) {
  return (quat_from_rpy(rpy).toRotationMatrix() * R_BG).cast<float>();
}

void require_points(std::span<const Eigen::Vector3f> points, const char* who) {
  if (points.empty()) throw Error(std::string(who) + " sampler: the object cloud is empty");
}
}  // namespace

std::vector<Candidate> sample_uniform(std::span<const Eigen::Vector3f> points,
                                      const SamplerConfig& cfg, const Eigen::Matrix3d& R_BG,
                                      std::uint64_t seed, std::uint32_t count, std::uint32_t first) {
  require_points(points, "uniform");
  std::vector<Candidate> out(count);
  const std::uint32_t n = cfg.variations;
  tbb::parallel_for(std::uint32_t(0), count, [&](std::uint32_t k) {
    const std::uint64_t i = std::uint64_t(first) + k;
    Rng pick(seed, kPick + i / n);  // the same uniformly drawn point for its n variations
    const auto j = static_cast<std::uint32_t>(pick.below(points.size()));
    Rng rng(seed, kUniform + i);
    Candidate& c = out[k];
    c.position = points[j] + normal3(rng, cfg.sigma_p).cast<float>();
    c.rotation = gripper_rotation(normal3(rng, cfg.sigma_theta), R_BG);
    c.source = static_cast<std::int32_t>(j);
  });
  return out;
}

std::vector<Candidate> sample_normal(std::span<const Eigen::Vector3f> points,
                                     const SamplerConfig& cfg, const Eigen::Matrix3d& R_BG,
                                     std::uint64_t seed, std::uint32_t count, std::uint32_t first) {
  require_points(points, "normal");
  std::vector<std::uint32_t> all(points.size());
  std::iota(all.begin(), all.end(), 0u);
  const MeanCovariance mc = mean_covariance(points, all);  // eq. 4.5, 4.4 over the object
  const Eigen::Vector3d& mean = mc.mean;
  const Eigen::Vector3d sigma = cfg.alpha_p.cwiseProduct(mc.cov.diagonal().cwiseSqrt());
  std::vector<Candidate> out(count);
  tbb::parallel_for(std::uint32_t(0), count, [&](std::uint32_t k) {
    Rng rng(seed, kNormal + first + k);
    Candidate& c = out[k];
    c.position = (mean + normal3(rng, sigma)).cast<float>();
    c.rotation = gripper_rotation(normal3(rng, cfg.sigma_theta), R_BG);
  });
  return out;
}

std::vector<Candidate> sample_surface(std::span<const Eigen::Vector3f> points,
                                      std::span<const Eigen::Vector3f> normals,
                                      const SamplerConfig& cfg, std::uint64_t seed,
                                      std::uint32_t count, std::uint32_t first) {
  require_points(points, "surface");
  if (normals.size() != points.size()) throw Error("surface sampler: the object has no normals");
  std::vector<Candidate> out(count);
  tbb::parallel_for(std::uint32_t(0), count, [&](std::uint32_t k) {
    Rng rng(seed, kSurface + first + k);
    const auto j = static_cast<std::uint32_t>(rng.below(points.size()));
    Eigen::Vector3d x = -normals[j].cast<double>();
    if (!(x.norm() > 0.5)) x = Eigen::Vector3d::UnitX();  // unusable normal: approach ahead
    x.normalize();
    // Closing direction: horizontal and perpendicular to the approach, then turned about it.
    Eigen::Vector3d y = Eigen::Vector3d::UnitZ().cross(x);
    if (y.norm() < 1e-3) y = Eigen::Vector3d::UnitY();
    y = (y - y.dot(x) * x).normalized();
    const double turn = rng.uniform() * std::numbers::pi;
    y = Eigen::AngleAxisd(turn, x) * y;
    Candidate& c = out[k];
    c.rotation.col(0) = x.cast<float>();
    c.rotation.col(1) = y.cast<float>();
    c.rotation.col(2) = x.cross(y).cast<float>();
    c.position = points[j] + normal3(rng, cfg.sigma_p).cast<float>();
    c.source = static_cast<std::int32_t>(j);
  });
  return out;
}

void check_sampler(const SamplerConfig& cfg) {
  const auto non_negative = [](const Eigen::Vector3d& v, const char* name) {
    if (!v.allFinite() || (v.array() < 0.0).any())
      throw Error(std::string("grasp.sampler.") + name + " must be finite and >= 0");
  };
  non_negative(cfg.sigma_theta, "sigma_theta");
  non_negative(cfg.sigma_p, "sigma_p");
  non_negative(cfg.alpha_p, "alpha_p");
  if (cfg.variations == 0) throw Error("grasp.sampler.variations must be at least 1");
  if (!(cfg.floor_clearance >= 0.0) || !std::isfinite(cfg.floor_clearance))
    throw Error("grasp.sampler.floor_clearance must be finite and >= 0");
  if (cfg.turns == 0 || cfg.turns > 360) throw Error("grasp.sampler.turns must be in [1, 360]");
  if (!(cfg.pilot > 0.0 && cfg.pilot <= 1.0 / 3.0))
    throw Error("grasp.sampler.pilot must be in (0, 1/3], got " + std::to_string(cfg.pilot));
}

const char* sampler_name(SamplerKind k) {
  switch (k) {
    case SamplerKind::uniform: return "uniform";
    case SamplerKind::normal: return "normal";
    case SamplerKind::surface: return "surface";
    case SamplerKind::antipodal: return "antipodal";
    case SamplerKind::automatic: return "auto";
  }
  return "?";
}

}  // namespace uwgrasp::grasp
