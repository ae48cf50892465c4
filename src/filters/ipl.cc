#include "src/filters/ipl.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {

double KlDivergence3(const Vec3& m0, const Mat3& p0, const Vec3& m1, const Mat3& p1) {
  const Eigen::LLT<Mat3> llt1(p1);
  const Eigen::LLT<Mat3> llt0(p0);
  const Mat3 l1 = llt1.matrixL();
  const Mat3 l0 = llt0.matrixL();
  const double log_det1 = 2.0 * l1.diagonal().array().log().sum();
  const double log_det0 = 2.0 * l0.diagonal().array().log().sum();
  const Vec3 dm = m1 - m0;
  return 0.5 * ((llt1.solve(p0)).trace() - log_det0 + log_det1 - 3.0 + dm.dot(llt1.solve(dm)));
}

IplResult PartitionedIpl(const Pose& prior_mean, const Mat3& prior_cov,
                         std::span<const IplPair> pairs, const Mat2& noise_cov,
                         const IplOptions& options) {
  IplResult lin{prior_mean, prior_cov, 0, false};
  for (int l = 1; l <= options.max_iterations; ++l) {
    Vec3 m = prior_mean;
    Mat3 p = prior_cov;
    for (const IplPair& pair : pairs) {
      const auto j = models::MeasurementJacobians(lin.mean, pair.landmark_mean);
      const Measurement z_hat = models::PredictMeasurement(lin.mean, pair.landmark_mean);
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
    if (!CholeskyLower<3>(p)) {
      lin.cholesky_failed = true;
      break;
    }
    const bool converged = l >= 2 && KlDivergence3(lin.mean, lin.cov, m, p) < options.kl_tolerance;
    lin.mean = m;
    lin.cov = p;
    lin.iterations = l;
    if (converged) break;
  }
  return lin;
}

}  // namespace phdslam::filters
