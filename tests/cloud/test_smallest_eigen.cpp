// smallest_eigen (normals.hpp) against Eigen's iterative SelfAdjointEigenSolver on covariances
// of known eigenvalues: well separated, nearly and exactly double or triple, zero, and scaled
// from 1e-12 to 1e6; and the invariants any answer must meet.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <vector>

#include "uwgrasp/cloud/normals.hpp"
#include "uwgrasp/core/rng.hpp"

namespace uwgrasp::cloud {
namespace {
Eigen::Matrix3d covariance(const Eigen::Vector3d& eigenvalues, Rng& rng) {
  const Eigen::Quaterniond q(Eigen::Vector4d(rng.uniform() - 0.5, rng.uniform() - 0.5,
                                             rng.uniform() - 0.5, rng.uniform() - 0.5)
                                 .normalized());
  const Eigen::Matrix3d r = q.toRotationMatrix();
  return r * eigenvalues.asDiagonal() * r.transpose();
}
}  // namespace

TEST(SmallestEigen, MatchesEigensSolverAndIsAnEigenpair) {
  Rng rng(5, 0);
  const std::vector<Eigen::Vector3d> spectra = {
      {1e-4, 0.5, 1.0},       {0.01, 0.02, 1.0},    {0.0, 0.3, 1.0},   {0.2, 0.2, 1.0},
      {0.2, 0.2 + 1e-9, 1.0}, {0.5, 1.0, 1.0},      {1.0, 1.0, 1.0},   {0.0, 0.0, 1.0},
      {1e-9, 1.0, 1.0},       {0.33, 0.331, 0.332}, {1e-7, 1e-7, 1.0}, {0.4, 0.6, 0.61}};
  int own = 0;  // answers not bit-equal to Eigen's closed form: the fast path was taken
  for (const double scale : {1e-12, 1e-6, 1.0, 1e6})
    for (const Eigen::Vector3d& ev : spectra)
      for (int t = 0; t < 200; ++t) {
        const Eigen::Matrix3d c = covariance(scale * ev, rng);
        const SmallestEigen got = smallest_eigen(c);
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> want(c);  // iterative: the oracle
        const double top = want.eigenvalues()[2];
        // A double root is found to about the square root of the rounding error (its
        // polynomial is flat there): 1e-8 of the largest eigenvalue.
        EXPECT_NEAR(got.value, std::max(0.0, want.eigenvalues()[0]), 1e-8 * top)
            << ev.transpose() << " x " << scale;
        EXPECT_NEAR(got.trace, c.trace(), 1e-9 * top);
        EXPECT_NEAR(got.vector.norm(), 1.0, 1e-12);
        // An eigenvector of the smallest eigenvalue, whatever the multiplicity.
        EXPECT_LE((c * got.vector - got.value * got.vector).norm(), 1e-7 * top)
            << ev.transpose() << " x " << scale;
        // And the solver's own where the smallest eigenvalue is separate.
        if (ev[1] - ev[0] > 1e-3 * ev[2]) {
          EXPECT_GT(std::abs(got.vector.dot(want.eigenvectors().col(0))), 1.0 - 1e-9)
              << ev.transpose() << " x " << scale;
        }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> direct;
        direct.computeDirect(c);
        own += got.value != std::max(0.0, direct.eigenvalues()[0]);
      }
  EXPECT_GT(own, 4000);  // of 9,600
}

TEST(SmallestEigen, ZeroAndNonFiniteMatricesDoNotCrash) {
  const SmallestEigen zero = smallest_eigen(Eigen::Matrix3d::Zero());
  EXPECT_EQ(zero.value, 0.0);
  EXPECT_NEAR(zero.vector.norm(), 1.0, 1e-12);
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(0, 1) = nan(1, 0) = std::numeric_limits<double>::quiet_NaN();
  smallest_eigen(nan);  // Eigen's answer, whatever it is: no crash under the sanitizers
  const PointNormal pn = normal_from_covariance(Eigen::Matrix3d::Zero(), {0, 0, 1}, {0, 0, 0});
  EXPECT_EQ(pn.curvature, 0.0f);
}

}  // namespace uwgrasp::cloud
