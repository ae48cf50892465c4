// The prediction of a pose Gaussian over one filter step (docs/algorithms/models.md section 2.4),
// shared by the RB-PHD-SLAM family, the oracle and dead reckoning.
#pragma once

#include "src/core/step_data.h"
#include "src/core/types.h"
#include "src/filters/estimator.h"

namespace phdslam::filters {

/// When the step has at least two time stamps: adds `regularisation` (Q_n) to `cov` once, then
/// for each sub-interval replaces `mean` by f(mean, u, dt) and `cov` by
/// Fx cov Fx^T + Fu Q_u Fu^T (symmetrised). A single-time-stamp step changes nothing.
void PredictPoseGaussian(const EstimatorContext& context, const StepData& step,
                         const Mat3& regularisation, Pose& mean, Mat3& cov);

}  // namespace phdslam::filters
