#include "reference/ceres/start_increments.h"

#include <stdexcept>
#include <string>

#include "src/core/angles.h"

namespace phdslam::reference {

std::vector<OdometryIncrement> StartTrajectoryIncrements(
    const datasets::Scenario& scenario, const std::vector<Pose>& start,
    const std::vector<OdometryIncrement>& odometry) {
  const std::size_t n = scenario.steps.size();
  if (start.size() != n || odometry.size() != n) {
    throw std::invalid_argument("StartTrajectoryIncrements: expected " + std::to_string(n) +
                                " start poses and increments, got " + std::to_string(start.size()) +
                                " and " + std::to_string(odometry.size()));
  }
  std::vector<OdometryIncrement> out = odometry;
  Pose previous = scenario.initial_pose;
  for (std::size_t k = 0; k < n; ++k) {
    if (!start[k].allFinite()) {
      throw std::invalid_argument("StartTrajectoryIncrements: start pose " + std::to_string(k) +
                                  " is not finite");
    }
    if (out[k].propagated) {
      Pose delta = RelativePose(previous, start[k]);
      delta(2) = WrapAngle(delta(2));
      out[k].delta = delta;
    }
    previous = start[k];
  }
  return out;
}

}  // namespace phdslam::reference
