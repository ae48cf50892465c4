// Shared test helper: every covariance a test checks goes through ExpectSymmetricPositiveDefinite.
// It is compiled once (positive_definite_check.cc) rather than instantiated in every test file:
// the eigen-decomposition it needs is the costliest template of the tests' compilation.
#pragma once

#include <Eigen/Core>

namespace phdslam::testing {

/// Expects P to be symmetric (to rounding: |P - P^T| <= sym_tol (1 + max |P_ij|)) with strictly
/// positive eigenvalues. Fixed-size matrices and expressions convert to Eigen::MatrixXd.
void ExpectSymmetricPositiveDefinite(const Eigen::MatrixXd& p, double sym_tol = 1e-12);

}  // namespace phdslam::testing
