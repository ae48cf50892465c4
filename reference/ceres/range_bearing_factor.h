// Range-bearing factor between a pose x and a landmark m for one measurement z = [r, phi]:
//
//   e = [h_r(m, x) - r;  wrap(h_phi(m, x) - phi)],   r = W e,   W^T W = R^{-1},
//
// with h the project's measurement model (src/models/range_bearing_model.h). Only the bearing
// difference is wrapped.
//
// Analytic Jacobians: the factor calls the model's PredictMeasurement and MeasurementJacobians
// (already checked against finite differences in src/models), so the measurement function has a
// single implementation, there is no templated angle wrap to write, and the tens of thousands of
// these factors in the paper scenario avoid dual-number arithmetic.
#pragma once

#include <ceres/sized_cost_function.h>

#include "src/core/types.h"

namespace phdslam::reference {

class RangeBearingFactor final : public ceres::SizedCostFunction<2, 3, 2> {
 public:
  RangeBearingFactor(const Measurement& z, const Mat2& whitening) : z_(z), whitening_(whitening) {}

  /// Fails (returns false, so the solver rejects the step) when the landmark coincides with the
  /// pose, where the bearing is undefined.
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  static ceres::CostFunction* Create(const Measurement& z, const Mat2& whitening) {
    return new RangeBearingFactor(z, whitening);
  }

  /// The unwhitened residual e at (x, m).
  [[nodiscard]] Vec2 Error(const Pose& x, const Landmark& m) const;

 private:
  Measurement z_;
  Mat2 whitening_;
};

}  // namespace phdslam::reference
