#include "reference/ceres/range_bearing_factor.h"

#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {

Vec2 RangeBearingFactor::Error(const Pose& x, const Landmark& m) const {
  const Measurement h = models::PredictMeasurement(x, m);
  return {h(0) - z_(0), WrapAngle(h(1) - z_(1))};
}

bool RangeBearingFactor::Evaluate(double const* const* parameters, double* residuals,
                                  double** jacobians) const {
  const Eigen::Map<const Pose> x(parameters[0]);
  const Eigen::Map<const Landmark> m(parameters[1]);
  const double r2 = (m - x.head<2>()).squaredNorm();
  if (!(r2 > 1e-18)) return false;
  Eigen::Map<Vec2> r(residuals);
  r = whitening_ * Error(x, m);
  if (jacobians == nullptr) return true;
  const models::RangeBearingJacobians j = models::MeasurementJacobians(x, m);
  if (jacobians[0] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> jx(jacobians[0]);
    jx = whitening_ * j.hx;
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 2, Eigen::RowMajor>> jm(jacobians[1]);
    jm = whitening_ * j.hm;
  }
  return true;
}

}  // namespace phdslam::reference
