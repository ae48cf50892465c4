#include "src/filters/pose_prediction.h"

#include "src/models/pose_propagation.h"

namespace phdslam::filters {

void PredictPoseGaussian(const EstimatorContext& context, const StepData& step,
                         const Mat3& regularisation, Pose& mean, Mat3& cov) {
  if (step.times.size() < 2) return;
  cov += regularisation;
  models::PropagatePoseGaussian(*context.motion, context.control_noise_cov, step, mean, cov);
}

}  // namespace phdslam::filters
