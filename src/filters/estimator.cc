#include "src/filters/estimator.h"

namespace phdslam::filters {

EstimatorContext EstimatorContext::FromScenario(const datasets::Scenario& s) {
  EstimatorContext c;
  c.initial_pose = s.initial_pose;
  c.motion = s.MakeMotionModel();
  c.control_noise_cov = s.control_noise_cov;
  c.sensor = s.sensor;
  return c;
}

}  // namespace phdslam::filters
