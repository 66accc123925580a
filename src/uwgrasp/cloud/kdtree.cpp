#include "uwgrasp/cloud/kdtree.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <nanoflann.hpp>
#include <string>

#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

namespace {
struct Adaptor {
  std::span<const Eigen::Vector3f> pts;
  std::size_t kdtree_get_point_count() const { return pts.size(); }
  float kdtree_get_pt(std::uint32_t i, std::size_t dim) const { return pts[i][dim]; }
  template <class B>
  bool kdtree_get_bbox(B&) const {
    return false;
  }
};
using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>,
                                                  Adaptor, 3, std::uint32_t>;
// Leaves of ~16 points balance build time against search time for 3-D scans.
constexpr std::size_t kLeafSize = 16;
}  // namespace

struct KdTree::Impl {
  Adaptor adaptor;
  Index index;
  explicit Impl(std::span<const Eigen::Vector3f> p)
      : adaptor{p}, index(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize)) {}
};

KdTree::KdTree(std::span<const Eigen::Vector3f> points) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!is_finite(points[i]))
      throw Error("kd-tree: point " + std::to_string(i) + " is not finite");
  }
  impl_ = std::make_unique<Impl>(points);
}

KdTree::~KdTree() = default;

std::size_t KdTree::size() const { return impl_->adaptor.pts.size(); }

std::size_t KdTree::knn(const Eigen::Vector3f& q, std::size_t k, std::uint32_t* indices,
                        float* sq_dists) const {
  if (k == 0 || size() == 0) return 0;
  return impl_->index.knnSearch(q.data(), k, indices, sq_dists);
}

void KdTree::radius(const Eigen::Vector3f& q, float r,
                    std::vector<std::pair<std::uint32_t, float>>& out) const {
  out.clear();
  if (size() == 0 || !(r > 0.0f)) return;
  impl_->index.radiusSearch(q.data(), r * r, out, nanoflann::SearchParams(32, 0.0f, true));
}

Neighbours knn_all(const KdTree& tree, std::span<const Eigen::Vector3f> queries, std::size_t k) {
  Neighbours nb;
  nb.k = k;
  nb.indices.resize(queries.size() * k);
  nb.sq_dists.resize(queries.size() * k);
  nb.count.resize(queries.size());
  if (k == 0) return nb;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, queries.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      nb.count[i] = static_cast<std::uint32_t>(
          tree.knn(queries[i], k, &nb.indices[i * k], &nb.sq_dists[i * k]));
    }
  });
  return nb;
}

}  // namespace uwgrasp::cloud
