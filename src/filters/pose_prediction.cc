#include "src/filters/pose_prediction.h"

#include "src/core/gaussian.h"

namespace phdslam::filters {

void PredictPoseGaussian(const EstimatorContext& context, const StepData& step,
                         const Mat3& regularisation, Pose& mean, Mat3& cov) {
  if (step.times.size() < 2) return;
  cov += regularisation;
  for (std::size_t i = 0; i + 1 < step.times.size(); ++i) {
    const double dt = step.times[i + 1] - step.times[i];
    const auto j = context.motion->Jacobians(mean, step.controls[i], dt);
    mean = context.motion->Predict(mean, step.controls[i], dt);
    cov = j.fx * cov * j.fx.transpose() + j.fu * context.control_noise_cov * j.fu.transpose();
    Symmetrize(cov);
  }
}

}  // namespace phdslam::filters
