#include "uwgrasp/eval/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::eval {

namespace {
// Ranks 1..n with ties sharing their mean rank.
std::vector<double> mid_ranks(const std::vector<double>& v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> rank(v.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    const double mean = 0.5 * double(i + j) + 1.0;
    for (std::size_t k = i; k <= j; ++k) rank[order[k]] = mean;
    i = j + 1;
  }
  return rank;
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = double(a.size());
  const double ma = std::accumulate(a.begin(), a.end(), 0.0) / n;
  const double mb = std::accumulate(b.begin(), b.end(), 0.0) / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}
}  // namespace

double spearman(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size())
    throw Error("spearman: " + std::to_string(a.size()) + " values against " + std::to_string(b.size()));
  if (a.empty()) return 0.0;
  return pearson(mid_ranks({a.begin(), a.end()}), mid_ranks({b.begin(), b.end()}));
}

Calibration calibrate(std::span<const double> score, std::span<const bool> success) {
  if (score.size() != success.size())
    throw Error("calibration: " + std::to_string(score.size()) + " scores for " +
                std::to_string(success.size()) + " outcomes");
  Calibration c;
  c.n = score.size();
  if (c.n == 0) return c;
  std::vector<double> s(score.begin(), score.end()), y(c.n);
  for (double& v : s)
    if (!std::isfinite(v)) v = -std::numeric_limits<double>::max();
  std::size_t positives = 0;
  for (std::size_t i = 0; i < c.n; ++i) positives += success[i] ? 1 : 0, y[i] = success[i] ? 1.0 : 0.0;
  c.base_rate = double(positives) / double(c.n);
  const std::vector<double> rs = mid_ranks(s);
  c.spearman = pearson(rs, mid_ranks(y));
  // Mann-Whitney U from the score ranks of the successes.
  const std::size_t negatives = c.n - positives;
  if (positives > 0 && negatives > 0) {
    double rank_sum = 0.0;
    for (std::size_t i = 0; i < c.n; ++i) rank_sum += success[i] ? rs[i] : 0.0;
    const double u = rank_sum - double(positives) * double(positives + 1) / 2.0;
    c.auc = u / (double(positives) * double(negatives));
  }
  std::vector<std::size_t> order(c.n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return s[a] > s[b]; });
  const std::size_t top = std::max<std::size_t>(1, c.n / 10);
  std::size_t held = 0;
  for (std::size_t i = 0; i < top; ++i) held += success[order[i]] ? 1 : 0;
  c.top_decile = double(held) / double(top);
  return c;
}

}  // namespace uwgrasp::eval
