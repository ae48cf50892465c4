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
#include "src/phd/map_params.h"

namespace phdslam::reference {

/// The prior of the map the score uses.
enum class PosteriorMapPrior {
  /// A Poisson point process of landmarks, as in the RFS filters: each landmark pays the birth
  /// intensity, -birth_log_weight, so that splitting a landmark or keeping clutter as one has a
  /// price (README.md, "The posterior of a solution").
  kPoissonBirth,
  /// No term per landmark: any number of landmarks is equally likely a priori.
  kFlat,
};

/// How a solution is scored.
struct PosteriorOptions {
  PosteriorMapPrior map_prior = PosteriorMapPrior::kPoissonBirth;
  /// Log of the Poisson birth intensity per landmark (per square metre, uniform over the map),
  /// the RFS filters' birth log-weight (phd::MapParams::birth_log_weight, ln 1e-6).
  double birth_log_weight = phd::MapParams{}.birth_log_weight;

  /// Throws std::invalid_argument naming the field when birth_log_weight is not finite.
  void Validate() const;
};

/// The terms of the negative log posterior, in nats. Terms that every hypothesis of the same data
/// shares (the odometry's normalisation, the Poisson clutter and detection constants, the birth
/// intensity's integral over the map) are left out, so only differences between solutions of the
/// same scenario mean anything.
struct PosteriorTerms {
  double odometry = 0.0;      ///< 1/2 of the squared whitened odometry residuals
  double measurements = 0.0;  ///< per associated measurement, 1/2 v^T R^-1 v + 1/2 log det(2 pi R)
  double detections = 0.0;    ///< per associated measurement, -log pD at its landmark
  double missed = 0.0;        ///< per step and landmark in the FOV not detected, -log(1 - pD)
  double clutter = 0.0;       ///< per measurement left unassociated, -log of the clutter intensity
  double births = 0.0;        ///< per landmark, -birth_log_weight (0 with the flat map prior)

  [[nodiscard]] double Total() const {
    return odometry + measurements + detections + missed + clutter + births;
  }
};

/// pD is held inside [kPosteriorMinPd, kPosteriorMaxPd] in the detection and missed terms: an
/// estimated landmark just outside the FOV (pD 0) that a measurement is associated with, or a
/// constant pD of 1 with a landmark not detected, would otherwise give an infinite term.
inline constexpr double kPosteriorMinPd = 1e-3;
inline constexpr double kPosteriorMaxPd = 0.999;

/// Scores `poses` (one per step), `landmarks` and `association` (per step, per measurement, an
/// index into `landmarks` or kUnassociated) with the odometry factors of `odometry` (the same
/// factors the graph solves with), the sensor's noise, detection profile and clutter intensity,
/// and the map prior of `options`. Throws std::invalid_argument when the sizes do not match the
/// scenario, an index is out of range or an option is invalid.
PosteriorTerms NegativeLogPosterior(const datasets::Scenario& scenario,
                                    const OdometrySpec& odometry, const std::vector<Pose>& poses,
                                    const std::vector<Landmark>& landmarks,
                                    const Association& association,
                                    const PosteriorOptions& options = {});

}  // namespace phdslam::reference
