// The negative log posterior of a smoother's solution: its trajectory, map and association scored
// under the scenario's own model (README.md, "The posterior of an association"). The own
// association's pass and the known association end at different solutions of the same data, and
// this number says which of the two the model prefers: a lower value for the known association
// than for the own one means the own association's search, not the model, is what fails.
#pragma once

#include <vector>

#include "datasets/scenario.h"
#include "reference/ceres/factor_graph.h"
#include "reference/ceres/landmark_association.h"
#include "src/core/types.h"

namespace phdslam::reference {

/// The terms of the negative log posterior, in nats. Terms that every hypothesis of the same data
/// shares (the odometry's normalisation, the Poisson clutter and detection constants) are left out,
/// and the map has a flat prior (no term per landmark), so only differences between solutions of
/// the same scenario mean anything.
struct PosteriorTerms {
  double odometry = 0.0;      ///< 1/2 of the squared whitened odometry residuals
  double measurements = 0.0;  ///< per associated measurement, 1/2 v^T R^-1 v + 1/2 log det(2 pi R)
  double detections = 0.0;    ///< per associated measurement, -log pD at its landmark
  double missed = 0.0;        ///< per step and landmark in the FOV not detected, -log(1 - pD)
  double clutter = 0.0;       ///< per measurement left unassociated, -log of the clutter intensity

  [[nodiscard]] double Total() const {
    return odometry + measurements + detections + missed + clutter;
  }
};

/// pD is held inside [kPosteriorMinPd, kPosteriorMaxPd] in the detection and missed terms: an
/// estimated landmark just outside the FOV (pD 0) that a measurement is associated with, or a
/// constant pD of 1 with a landmark not detected, would otherwise give an infinite term.
inline constexpr double kPosteriorMinPd = 1e-3;
inline constexpr double kPosteriorMaxPd = 0.999;

/// Scores `poses` (one per step), `landmarks` and `association` (per step, per measurement, an
/// index into `landmarks` or kUnassociated) with the odometry factors of `odometry` (the same
/// factors the graph solves with), the sensor's noise, detection profile and clutter intensity.
/// Throws std::invalid_argument when the sizes do not match the scenario or an index is out of
/// range.
PosteriorTerms NegativeLogPosterior(const datasets::Scenario& scenario,
                                    const OdometrySpec& odometry, const std::vector<Pose>& poses,
                                    const std::vector<Landmark>& landmarks,
                                    const Association& association);

}  // namespace phdslam::reference
