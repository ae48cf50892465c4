// A landmark's marginal covariance made symmetric positive definite before it becomes a Gaussian
// prior (docs/algorithms/ceres-smoother.md section 8): a marginal taken from a near-singular
// window can be indefinite by rounding, and a prior must be positive definite.
#pragma once

#include <Eigen/Eigenvalues>

#include "src/core/gaussian.h"
#include "src/core/types.h"

namespace phdslam::reference {

/// Smallest eigenvalue a landmark covariance keeps: (1e-4 m)^2.
inline constexpr double kLandmarkVarianceFloor = 1e-8;

/// The symmetric part of `cov` with its eigenvalues floored at kLandmarkVarianceFloor; the
/// identity (1 m^2 per axis) when `cov` is not finite. A covariance whose eigenvalues are all
/// above the floor comes back equal to its symmetric part up to rounding.
inline Mat2 FlooredLandmarkCovariance(const Mat2& cov) {
  if (!cov.allFinite()) return Mat2::Identity();
  const Eigen::SelfAdjointEigenSolver<Mat2> eig(0.5 * (cov + cov.transpose()));
  const Vec2 l = eig.eigenvalues().cwiseMax(kLandmarkVarianceFloor);
  Mat2 out = eig.eigenvectors() * l.asDiagonal() * eig.eigenvectors().transpose();
  Symmetrize(out);
  return out;
}

}  // namespace phdslam::reference
