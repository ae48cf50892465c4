#include "src/testing/positive_definite_check.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

namespace phdslam::testing {

void ExpectSymmetricPositiveDefinite(const Eigen::MatrixXd& p, double sym_tol) {
  EXPECT_LE((p - p.transpose()).cwiseAbs().maxCoeff(), sym_tol * (1.0 + p.cwiseAbs().maxCoeff()));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(p);
  EXPECT_GT(es.eigenvalues().minCoeff(), 0.0) << "matrix:\n" << p;
}

}  // namespace phdslam::testing
