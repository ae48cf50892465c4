// The scenario linearised at its truth (linearised_slam.h) for one of the bounds' detection
// models (pcrb_params.h): the motion Jacobians along the true trajectory, the detections that
// carry information and their information scale.
#pragma once

#include <cstdint>
#include <string>

#include "datasets/scenario.h"
#include "reference/pcrb/linearised_slam.h"
#include "reference/pcrb/pcrb_params.h"

namespace phdslam::reference::pcrb {

/// Throws std::invalid_argument naming `who` (the estimator) and the scenario when the scenario
/// has no true trajectory or map (real data such as Victoria Park), when Q_u or R is not finite
/// and positive definite, when the detection probability is 0, or when the conditioned model is
/// asked for a scenario without origin labels. `stream_seed` drives the reduction factor's
/// Monte Carlo integral.
LinearisedSlam Linearise(const datasets::Scenario& scenario, const PcrbParams& params,
                         std::uint64_t stream_seed, const std::string& who);

/// Clutter per unit whitened measurement area: the simulators' clutter is uniform in the
/// (range, bearing) box of the field of view, lambda / (2 Theta R), times sqrt(det R).
double WhitenedClutterDensity(const models::SensorModel& sensor);

}  // namespace phdslam::reference::pcrb
