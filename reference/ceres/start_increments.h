// The odometry increments that follow a start trajectory (README.md, "Start from another
// estimator's trajectory"): the smoother's sequential association pass predicts each pose by the
// start trajectory's relative motion instead of the odometry. Below both the smoother
// (batch_smoother.cc uses them) and SmoothFromEstimatorStart (start_trajectory.h), which runs
// the smoother.
#pragma once

#include <vector>

#include "datasets/scenario.h"
#include "reference/ceres/odometry_increment.h"
#include "src/core/types.h"

namespace phdslam::reference {

/// The increments that follow `start` (one pose per step of `scenario`): step k's delta is
/// start[k] in the frame of start[k-1] (start[-1] = scenario.initial_pose), the heading
/// difference wrapped to (-pi, pi] (estimators report wrapped headings). A step without
/// propagation in `odometry` stays without; every covariance is `odometry`'s, so the pass gates
/// and weighs its pose corrections as it would from dead reckoning. Throws std::invalid_argument
/// when the sizes differ or a start pose is not finite.
std::vector<OdometryIncrement> StartTrajectoryIncrements(
    const datasets::Scenario& scenario, const std::vector<Pose>& start,
    const std::vector<OdometryIncrement>& odometry);

}  // namespace phdslam::reference
