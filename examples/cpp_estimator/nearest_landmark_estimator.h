// A deliberately simple online estimator, written outside phdslam against its installed headers:
// dead reckoning for the pose, and a map that averages the landmark positions the measurements
// point to, each merged into the nearest landmark within `merge_distance` (else a new one).
#pragma once

#include <memory>
#include <vector>

#include "src/core/parameter_table.h"
#include "src/filters/estimator.h"

namespace example {

struct NearestLandmarkParams {
  double merge_distance = 5.0;  ///< m
  int confirm_hits = 3;         ///< detections before a landmark is reported in the map
};

/// The declarative parameter table (JSON, --set-style overrides and their checks).
const phdslam::params::ParameterTable<NearestLandmarkParams>& NearestLandmarkParamsTable();

class NearestLandmarkEstimator final : public phdslam::filters::OnlineEstimator {
 public:
  NearestLandmarkEstimator(const phdslam::filters::EstimatorContext& context,
                           const NearestLandmarkParams& params);
  phdslam::filters::StepOutput Step(const phdslam::StepData& step) override;
  [[nodiscard]] phdslam::filters::MapEstimate Map() const override;

 private:
  struct Landmark {
    phdslam::Landmark sum = phdslam::Landmark::Zero();
    int hits = 0;
    [[nodiscard]] phdslam::Landmark Mean() const { return sum / hits; }
  };
  std::shared_ptr<const phdslam::models::MotionModel> motion_;
  NearestLandmarkParams params_;
  phdslam::Pose pose_;
  std::vector<Landmark> landmarks_;
};

}  // namespace example
