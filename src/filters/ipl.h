// Partitioned iterated posterior linearisation of the pose (Algorithm 1 of the PHD-SLAM 3.0
// paper, docs/algorithms/phd-slam.md section 4.5). Shared by the GM importance density of PHD-SLAM
// 3.0 and by the oracle RBPF.
#pragma once

#include <span>

#include "src/core/types.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {

/// One associated (landmark Gaussian, measurement) pair of an IPL update.
struct IplPair {
  Landmark landmark_mean;
  Mat2 landmark_cov;
  Measurement z;
  /// h and its Jacobians at (prior mean, landmark_mean), when the caller has already evaluated
  /// them there (the association costs do): iteration 1 linearises at the prior and takes them
  /// from here instead of evaluating again. The same values, so the same result bit for bit.
  const models::PredictionWithJacobians* at_prior = nullptr;
};

struct IplOptions {
  int max_iterations = 5;      ///< L
  double kl_tolerance = 1e-3;  ///< epsilon: stop when KL(previous || new) < epsilon
};

struct IplResult {
  Pose mean;
  Mat3 cov;
  int iterations = 0;  ///< iterations whose result was accepted
  bool cholesky_failed = false;
};

/// Runs the IPL from the prior N(prior_mean, prior_cov) over `pairs`, processed in the given
/// order. Each iteration restarts from the prior and linearises every pair at the previous
/// iterate (the prior in iteration 1); the KL test starts at iteration 2; when the updated
/// covariance is not positive definite the previous iterate is kept.
/// The statistical linear regression is first order, so A = Hx and
/// Omega = Hm P Hm^T + R (the reference code forms the same quantities through an explicit
/// inverse of the linearisation covariance; they agree analytically).
IplResult PartitionedIpl(const Pose& prior_mean, const Mat3& prior_cov,
                         std::span<const IplPair> pairs, const Mat2& noise_cov,
                         const IplOptions& options);

/// KL(N(m0, P0) || N(m1, P1)) for 3-D Gaussians with positive-definite P0 and P1, the convergence
/// measure of the IPL.
double KlDivergence3(const Vec3& m0, const Mat3& p0, const Vec3& m1, const Mat3& p1);

}  // namespace phdslam::filters
