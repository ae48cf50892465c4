// Range-bearing measurement model, its Jacobians and inverse model (reference notes section 5).
#pragma once

#include "src/core/types.h"

namespace phdslam::models {

struct RangeBearingJacobians {
  Mat23 hx;  ///< d h / d pose
  Mat2 hm;   ///< d h / d landmark
};

/// h(m, x) = [r, wrap(atan2(dy, dx) - theta)].
Measurement PredictMeasurement(const Pose& x, const Landmark& m);
/// Jacobians of h at (x, m).
RangeBearingJacobians MeasurementJacobians(const Pose& x, const Landmark& m);
/// Inverse model: the landmark a measurement z taken at pose x points to.
Landmark InverseMeasurement(const Pose& x, const Measurement& z);
/// Jacobian of the inverse model with respect to z.
Mat2 InverseMeasurementJacobian(const Pose& x, const Measurement& z);
/// Birth covariance G R G^T (no pose-uncertainty term).
Mat2 BirthCovariance(const Pose& x, const Measurement& z, const Mat2& r);

}  // namespace phdslam::models
