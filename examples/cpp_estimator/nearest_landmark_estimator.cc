#include "nearest_landmark_estimator.h"

#include <cmath>
#include <limits>

#include "src/models/range_bearing_model.h"

namespace example {

const phdslam::params::ParameterTable<NearestLandmarkParams>& NearestLandmarkParamsTable() {
  using phdslam::params::Above;
  using phdslam::params::AtLeast;
  static const phdslam::params::ParameterTable<NearestLandmarkParams> table({
      phdslam::params::NumberField<NearestLandmarkParams>(
          "merge_distance", [](auto& p) -> auto& { return p.merge_distance; }, Above(0.0))
          .Means("a measurement closer than this (m) to a mapped landmark is that landmark"),
      phdslam::params::IntField<NearestLandmarkParams>(
          "confirm_hits", [](auto& p) -> auto& { return p.confirm_hits; }, AtLeast(1))
          .Means("detections before a landmark enters the map"),
  });
  return table;
}

NearestLandmarkEstimator::NearestLandmarkEstimator(
    const phdslam::filters::EstimatorContext& context, const NearestLandmarkParams& params)
    : motion_(context.motion), params_(params), pose_(context.initial_pose) {}

phdslam::filters::StepOutput NearestLandmarkEstimator::Step(const phdslam::StepData& step) {
  for (std::size_t i = 0; i < step.controls.size(); ++i) {
    pose_ = motion_->Predict(pose_, step.controls[i], step.times[i + 1] - step.times[i]);
  }
  phdslam::filters::StepOutput out;
  out.pose = pose_;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const phdslam::Measurement& z : step.measurements) {
    const phdslam::Landmark m = phdslam::models::InverseMeasurement(pose_, z);
    Landmark* nearest = nullptr;
    double best = params_.merge_distance;
    for (Landmark& l : landmarks_) {
      const double d = (l.Mean() - m).norm();
      if (d <= best) {
        best = d;
        nearest = &l;
      }
    }
    if (nearest == nullptr) {
      landmarks_.push_back({m, 1});
      out.association.emplace_back(nan, nan);
      continue;
    }
    out.association.push_back(nearest->Mean());
    nearest->sum += m;
    ++nearest->hits;
  }
  return out;
}

phdslam::filters::MapEstimate NearestLandmarkEstimator::Map() const {
  phdslam::filters::MapEstimate map;
  for (const Landmark& l : landmarks_) {
    if (l.hits < params_.confirm_hits) continue;
    map.means.push_back(l.Mean());
    map.log_weights.push_back(0.0);
  }
  return map;
}

}  // namespace example
