#pragma once
// k-d tree neighbour search over a cloud's points (thesis 4.1.2), backed by nanoflann.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace uwgrasp::cloud {

class KdTree {
 public:
  // Indexes `points`, which must stay alive and unchanged while the tree is used. Throws Error if
  // a point is not finite.
  explicit KdTree(std::span<const Eigen::Vector3f> points);
  ~KdTree();
  KdTree(const KdTree&) = delete;
  KdTree& operator=(const KdTree&) = delete;

  std::size_t size() const;
  std::span<const Eigen::Vector3f> points() const;
  // The k nearest points to q, nearest first; returns how many were found (< k only when the
  // tree has fewer points). Distances are squared.
  std::size_t knn(const Eigen::Vector3f& q, std::size_t k, std::uint32_t* indices,
                  float* sq_dists) const;
  // Whether some point lies within `radius` of q (squared distance <= radius^2, the test knn's
  // nearest would pass): the search prunes at the radius from the start and stops at the first
  // such point, so it is cheaper than knn(q, 1), most of all where no point is near.
  bool any_within(const Eigen::Vector3f& q, float radius) const;
  // All points within `radius` of q, nearest first, as (index, squared distance).
  void radius(const Eigen::Vector3f& q, float radius,
              std::vector<std::pair<std::uint32_t, float>>& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// k nearest neighbours of many query points, computed in parallel: row i holds count[i] valid
// entries of indices/sq_dists starting at i*k, nearest first. Lists from an organised frame's
// pixel windows (organised.hpp) have `window` set: each row is the point itself, then its whole
// window's neighbours in pixel order, not sorted by distance - consumers take every entry.
struct Neighbours {
  std::size_t k = 0;
  bool window = false;
  std::vector<std::uint32_t> indices;
  std::vector<float> sq_dists;
  std::vector<std::uint32_t> count;
  std::span<const std::uint32_t> of(std::size_t i) const { return {&indices[i * k], count[i]}; }
  std::span<const float> dists_of(std::size_t i) const { return {&sq_dists[i * k], count[i]}; }
};
Neighbours knn_all(const KdTree& tree, std::span<const Eigen::Vector3f> queries, std::size_t k);

// The k nearest neighbours among a subset of the tree's points, for each point of the subset,
// from lists already found over all of them: `all` = knn_all(tree, tree.points(), K), and `kept`
// the subset's indices in the tree (ascending). Row j holds indices into `kept`. Removed points
// are skipped; a row they leave short of k is searched again, wider, so the lists are exact:
// the same distances as knn_all over the subset alone (k is capped at kept.size()).
Neighbours restrict_neighbours(const KdTree& tree, const Neighbours& all,
                               std::span<const std::uint32_t> kept, std::size_t k);

}  // namespace uwgrasp::cloud
