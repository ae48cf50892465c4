#include "src/filters/ipl.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "src/core/angles.h"
#include "src/core/cholesky3.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {

namespace {

/// The Cholesky factorisation of a 3x3 covariance with its log-determinant (NaN when it is not
/// positive definite).
struct Factorised3 {
  Cholesky3 factor;
  double log_det;
  /// What CholeskyLower<3> accepts.
  [[nodiscard]] bool PositiveDefinite() const { return factor.positive_definite(); }
};

Factorised3 Factorise(const Mat3& p) {
  const Cholesky3 factor(p);
  return {factor,
          factor.positive_definite() ? factor.LogDet() : std::numeric_limits<double>::quiet_NaN()};
}

/// KL(N(m0, P0) || N(m1, P1)) given log det P0 and the factorisation of P1.
double KlDivergenceFactorised(const Vec3& m0, const Mat3& p0, double log_det0, const Vec3& m1,
                              const Factorised3& p1) {
  const Vec3 dm = m1 - m0;
  return 0.5 *
         (p1.factor.TraceOfSolve(p0) - log_det0 + p1.log_det - 3.0 + dm.dot(p1.factor.Solve(dm)));
}

}  // namespace

double KlDivergence3(const Vec3& m0, const Mat3& p0, const Vec3& m1, const Mat3& p1) {
  return KlDivergenceFactorised(m0, p0, Factorise(p0).log_det, m1, Factorise(p1));
}

IplResult PartitionedIpl(const Pose& prior_mean, const Mat3& prior_cov,
                         std::span<const IplPair> pairs, const Mat2& noise_cov,
                         const IplOptions& options) {
  IplResult lin{prior_mean, prior_cov, 0, false};
  double lin_log_det = 0.0;  // log det lin.cov, from iteration 1 on (when the KL test needs it)
  for (int l = 1; l <= options.max_iterations; ++l) {
    Vec3 m = prior_mean;
    Mat3 p = prior_cov;
    for (const IplPair& pair : pairs) {
      const auto [z_hat, j] = l == 1 && pair.at_prior != nullptr
                                  ? *pair.at_prior
                                  : models::PredictWithJacobians(lin.mean, pair.landmark_mean);
      const Mat2 omega = j.hm * pair.landmark_cov * j.hm.transpose() + noise_cov;
      // nu = z - (A m + b) with A = Hx, b = z_hat - A mu_bar.
      Vec2 nu = pair.z - z_hat - j.hx * (m - lin.mean);
      nu(1) = WrapAngle(nu(1));
      const Mat32 pa = p * j.hx.transpose();
      Mat2 s = j.hx * pa + omega;
      Symmetrize(s);
      const Mat32 k = pa * s.inverse();
      m += k * nu;
      p -= k * s * k.transpose();
      Symmetrize(p);
    }
    // One factorisation of p serves the positive-definiteness test, this iteration's KL test and
    // (its log-determinant) the next one's.
    const Factorised3 factor = Factorise(p);
    if (!factor.PositiveDefinite()) {
      lin.cholesky_failed = true;
      break;
    }
    const bool converged = l >= 2 && KlDivergenceFactorised(lin.mean, lin.cov, lin_log_det, m,
                                                            factor) < options.kl_tolerance;
    lin.mean = m;
    lin.cov = p;
    lin_log_det = factor.log_det;
    lin.iterations = l;
    if (converged) break;
  }
  return lin;
}

}  // namespace phdslam::filters
