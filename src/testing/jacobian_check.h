// Shared test helpers: every analytic Jacobian in phdslam is checked against central finite
// differences with ExpectJacobianNear, and every covariance with ExpectSymmetricPositiveDefinite
// (src/testing/positive_definite_check.h).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <initializer_list>

#include "src/testing/positive_definite_check.h"

namespace phdslam::testing {

/// Central-difference Jacobian of f at x. `wrap_rows` lists output rows that are angles: their
/// differences are wrapped into [-pi, pi] before dividing by the step.
template <int M, int N>
Eigen::Matrix<double, M, N> NumericJacobian(
    const std::function<Eigen::Matrix<double, M, 1>(const Eigen::Matrix<double, N, 1>&)>& f,
    const Eigen::Matrix<double, N, 1>& x, double step = 1e-6,
    std::initializer_list<int> wrap_rows = {}) {
  Eigen::Matrix<double, M, N> j;
  for (int c = 0; c < N; ++c) {
    Eigen::Matrix<double, N, 1> xp = x;
    Eigen::Matrix<double, N, 1> xm = x;
    xp(c) += step;
    xm(c) -= step;
    Eigen::Matrix<double, M, 1> d = f(xp) - f(xm);
    for (int r : wrap_rows) d(r) = std::remainder(d(r), 2.0 * M_PI);
    j.col(c) = d / (2.0 * step);
  }
  return j;
}

/// Expects the analytic Jacobian to match the central-difference one entrywise, with a tolerance
/// relative to the entry's magnitude.
template <int M, int N>
void ExpectJacobianNear(
    const Eigen::Matrix<double, M, N>& analytic,
    const std::function<Eigen::Matrix<double, M, 1>(const Eigen::Matrix<double, N, 1>&)>& f,
    const Eigen::Matrix<double, N, 1>& x, double tol = 1e-6,
    std::initializer_list<int> wrap_rows = {}) {
  const Eigen::Matrix<double, M, N> numeric = NumericJacobian<M, N>(f, x, 1e-6, wrap_rows);
  for (int r = 0; r < M; ++r) {
    for (int c = 0; c < N; ++c) {
      EXPECT_NEAR(analytic(r, c), numeric(r, c), tol * (1.0 + std::abs(numeric(r, c))))
          << "Jacobian entry (" << r << ", " << c << ")\nanalytic:\n"
          << analytic << "\nnumeric:\n"
          << numeric;
    }
  }
}

}  // namespace phdslam::testing
