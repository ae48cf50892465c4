#include "reference/pcrb/pcrb_estimator.h"

#include <chrono>

#include "reference/pcrb/filtering_bound.h"
#include "reference/pcrb/linearise.h"
#include "reference/pcrb/smoothing_bound.h"

namespace phdslam::reference::pcrb {

datasets::BatchResult PcrbEstimator::Solve(const datasets::Scenario& scenario) {
  const auto start = std::chrono::steady_clock::now();
  const LinearisedSlam model = Linearise(scenario, params_, stream_seed_, name_);
  const FilteringBound filtering = ComputeFilteringBound(model);
  const std::vector<Mat3> covs = kind_ == BoundKind::kSmoothing
                                     ? ComputeSmoothingBound(model, filtering)
                                     : filtering.pose_covs;
  datasets::BatchResult result;
  result.poses = scenario.truth.poses;
  result.pose_covs.assign(covs.begin(), covs.end());
  for (std::size_t i = 0; i < filtering.landmark_seen.size(); ++i) {
    if (!filtering.landmark_seen[i]) continue;
    result.map.means.push_back(scenario.truth.landmarks[i]);
    result.map.covs.push_back(filtering.landmark_covs[i]);
    result.map.log_weights.push_back(0.0);
  }
  result.solve_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace phdslam::reference::pcrb
