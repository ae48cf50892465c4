// Range-bearing measurement model, its Jacobians and inverse model (docs/algorithms/models.md
// section 3.1-3.2).
#pragma once

#include <cmath>

#include "src/core/angles.h"
#include "src/core/types.h"

namespace phdslam::models {

struct RangeBearingJacobians {
  Mat23 hx;  ///< d h / d pose
  Mat2 hm;   ///< d h / d landmark
};

/// h(m, x) = [r, wrap(atan2(dy, dx) - theta)].
inline Measurement PredictMeasurement(const Pose& x, const Landmark& m) {
  const double dx = m(0) - x(0);
  const double dy = m(1) - x(1);
  return {std::sqrt(dx * dx + dy * dy), WrapAngle(std::atan2(dy, dx) - x(2))};
}

/// Jacobians of h at (x, m), given the offsets dx, dy of m from x, q = dx^2 + dy^2 and r = sqrt(q).
inline RangeBearingJacobians JacobiansFromOffsets(double dx, double dy, double q, double r) {
  RangeBearingJacobians j;
  j.hm << dx / r, dy / r, -dy / q, dx / q;
  j.hx << -dx / r, -dy / r, 0.0, dy / q, -dx / q, -1.0;
  return j;
}

/// Jacobians of h at (x, m).
inline RangeBearingJacobians MeasurementJacobians(const Pose& x, const Landmark& m) {
  const double dx = m(0) - x(0);
  const double dy = m(1) - x(1);
  const double q = dx * dx + dy * dy;
  return JacobiansFromOffsets(dx, dy, q, std::sqrt(q));
}

/// h(m, x) and its Jacobians from one evaluation of the offsets: the same values, bit for bit, as
/// PredictMeasurement and MeasurementJacobians, for the hot loops that need both.
struct PredictionWithJacobians {
  Measurement z_hat;
  RangeBearingJacobians j;
};
inline PredictionWithJacobians PredictWithJacobians(const Pose& x, const Landmark& m) {
  const double dx = m(0) - x(0);
  const double dy = m(1) - x(1);
  const double q = dx * dx + dy * dy;
  const double r = std::sqrt(q);
  return {{r, WrapAngle(std::atan2(dy, dx) - x(2))}, JacobiansFromOffsets(dx, dy, q, r)};
}
/// Inverse model: the landmark a measurement z taken at pose x points to.
Landmark InverseMeasurement(const Pose& x, const Measurement& z);
/// Jacobian of the inverse model with respect to z.
Mat2 InverseMeasurementJacobian(const Pose& x, const Measurement& z);
/// Birth covariance G R G^T (no pose-uncertainty term).
Mat2 BirthCovariance(const Pose& x, const Measurement& z, const Mat2& r);
/// InverseMeasurement and BirthCovariance from one sine and cosine: the same values, bit for bit.
struct BirthGaussian {
  Landmark mean;
  Mat2 cov;
};
BirthGaussian BirthFromMeasurement(const Pose& x, const Measurement& z, const Mat2& r);

}  // namespace phdslam::models
