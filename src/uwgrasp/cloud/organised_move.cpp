// Points moved along their rays onto quadratics fitted to their windows' ranges (organised.hpp,
// move_onto_quadrics).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/organised_window.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

using namespace window_detail;

namespace {
// The most a point moves, in continuity allowances of one pixel step (depth_change x range):
// farther, the window's fit is not its surface (a thin part, a crease the window straddles).
constexpr float kMaxMove = 3.0f;
// A cut window's fit needs twice the quadratic's six terms, and a system that is not singular
// (its pixels on one line, a one-pixel-wide strip).
constexpr std::size_t kMinPixels = 12;
constexpr double kMinRcond = 1e-9;

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

Vec6 terms(double du, double dv) {
  Vec6 a;
  a << 1.0, du, dv, du * du, du * dv, dv * dv;
  return a;
}

// The fitted range at the centre pixel minus its own, for a window the continuity cut or the
// frame's edge left short: the least-squares quadratic in the pixel offsets. NaN when the
// window's pixels do not fix it.
double cut_window_move(std::span<const std::uint32_t> list, const PixelMap& map,
                       std::span<const float> range) {
  if (list.size() < kMinPixels) return std::numeric_limits<double>::quiet_NaN();
  const std::uint32_t p0 = map.pixel[list[0]];
  const double u0 = p0 % map.width, v0 = p0 / map.width, r0 = range[list[0]];
  Mat6 ata = Mat6::Zero();
  Vec6 atb = Vec6::Zero();
  for (const std::uint32_t s : list) {
    const std::uint32_t p = map.pixel[s];
    const Vec6 a = terms(double(p % map.width) - u0, double(p / map.width) - v0);
    ata.selfadjointView<Eigen::Lower>().rankUpdate(a);
    atb += a * (double(range[s]) - r0);
  }
  const Eigen::LDLT<Mat6> ldlt(ata.selfadjointView<Eigen::Lower>().toDenseMatrix());
  if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > kMinRcond))
    return std::numeric_limits<double>::quiet_NaN();
  return ldlt.solve(atb)(0);
}
}  // namespace

QuadraticKernel quadratic_kernel(std::uint32_t h) {
  // The centre value of a least-squares quadratic over a whole (2h+1)^2 window weighs each pixel
  // alpha + beta (du^2 + dv^2) (the odd and cross terms' weights vanish by symmetry); the
  // weights sum to 1 and give u^2 and v^2 no weight. With m = 2h+1 and the 1-D sums S2 of du^2
  // and S4 of du^4: alpha m^2 + 2 beta m S2 = 1, alpha m S2 + beta (m S4 + S2^2) = 0.
  const double m = 2.0 * h + 1.0, s2 = h * (h + 1.0) * m / 3.0,
               s4 = h * (h + 1.0) * m * (3.0 * h * h + 3.0 * h - 1.0) / 15.0;
  const double ratio = -m * s2 / (m * s4 + s2 * s2);  // beta / alpha
  QuadraticKernel k;
  k.alpha = 1.0 / (m * m + 2.0 * m * s2 * ratio);
  k.beta = ratio * k.alpha;
  return k;  // the sum of the squared weights is alpha: the noise left is sigma sqrt(alpha)
}

MovedOntoQuadrics move_onto_quadrics(Cloud& cloud, const PixelMap& map, const OrganisedConfig& cfg,
                                     WindowScratch& scratch) {
  check_window(cfg.normal_half_window);
  if (map.pixel.size() != cloud.size())
    throw Error("move_onto_quadrics: the pixel map does not fit this cloud");
  const std::span<const float> range = ranges(cloud.points, cloud.viewpoint, scratch.range);
  const WindowTable table(map.width, cfg.normal_half_window);
  const QuadraticKernel k = quadratic_kernel(cfg.normal_half_window);
  std::array<float, kMaxWindow> weight{};  // a whole window's weights, in the table's order
  for (std::size_t i = 0; i < table.size; ++i) {
    const int du = table.col[i], dv = table.row[i];
    weight[i] = float(k.alpha + k.beta * double(du * du + dv * dv));
  }
  std::vector<float>& move = scratch.move;  // each point's move along its ray, NaN: none
  move.resize(cloud.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 1024), [&](const auto& r) {
    std::array<std::uint32_t, kMaxWindow> list;  // a window's pixels (check_window above)
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const std::size_t n =
          window_list(cloud.points, map, table, cfg.depth_change, range, j, list.data(), nullptr);
      double t = 0.0;
      if (n == table.size + 1) {  // whole: the list is in the table's order, after the point
        for (std::size_t i = 0; i < table.size; ++i)
          t += double(weight[i]) * double(range[list[i + 1]] - range[j]);
      } else {
        t = cut_window_move({list.data(), n}, map, range);
      }
      const bool keep = std::abs(t) <= double(kMaxMove * cfg.depth_change * range[j]);
      move[j] = keep ? float(t) : std::numeric_limits<float>::quiet_NaN();  // NaN fails too
    }
  });
  // Every move from the ranges as they were, then applied: no point's fit saw a moved one.
  // The moves' sizes over range^2 measure the noise they took out as a depth camera's law.
  std::vector<float>& size = scratch.sample;
  size.clear();
  for (std::size_t j = 0; j < cloud.size(); ++j) {
    if (std::isnan(move[j])) continue;
    const float rj = std::max(range[j], 1e-6f);
    cloud.points[j] += move[j] / rj * (cloud.points[j] - cloud.viewpoint);
    size.push_back(std::abs(move[j]) / (rj * rj));
  }
  MovedOntoQuadrics out;
  if (size.empty()) return out;
  const auto mid = size.begin() + std::ptrdiff_t(size.size() / 2);
  std::nth_element(size.begin(), mid, size.end());
  // A move is the fit's error minus the point's own: deviation sigma sqrt(1 - alpha); a normal
  // deviate's median |x| is 0.6745 sigma.
  out.noise = 1.4826 * double(*mid) / std::sqrt(1.0 - k.alpha);
  out.left = out.noise * std::sqrt(k.alpha);
  return out;
}

}  // namespace uwgrasp::cloud
