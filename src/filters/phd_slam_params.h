// Parameters of the RB-PHD-SLAM family (docs/algorithms/phd-slam.md section 7). Defaults are the
// paper's synthetic-scenario values; the defaults that depend on the scenario (Victoria Park's) are
// in the runner's table of scenario defaults (validation/runner/registry/scenario_defaults.cc).
#pragma once

#include <cmath>

#include "src/core/types.h"
#include "src/filters/particle_filter_params.h"
#include "src/filters/rb_phd_weighting.h"
#include "src/phd/map_params.h"

namespace phdslam::filters {

struct PhdSlamParams {
  int particles = 1;
  phd::MapParams map;

  /// Maximum number of Murty hypotheses in the GM importance density (J-bar); 0 gives the
  /// transition density (PHD-SLAM 1.0).
  int max_hypotheses = 50;
  /// Murty early stop: total-cost gap to the best hypothesis, -ln(1e-3).
  double murty_max_cost_gap = 6.907755278982137;
  /// Reference code: an extra all-clutter component (prior mean and covariance) in the mixture.
  bool all_clutter_component = true;
  int ipl_iterations = 5;
  double ipl_kl_tolerance = 1e-3;

  /// Resampling: enabled and threshold (0 disables).
  bool resampling = true;
  EssThresholdKind ess_threshold_kind = EssThresholdKind::kRelative;
  double ess_threshold = 0.2;

  /// Regularising pose noise added once per step before propagation.
  Mat3 pose_regularisation = Vec3(1e-9, 1e-9, 1e-18).asDiagonal();

  /// Map estimate threshold ln((1 - pD_nominal)^2); NaN means derive it from the sensor.
  double estimate_log_weight_threshold = std::nan("");

  /// Particle weight: PHD-SLAM 3.0's eq. 46 as the reference code evaluates it (default), or
  /// Mullane et al.'s empty-map or single-feature strategy (rb_phd_weighting.h).
  RbPhdWeighting weighting = RbPhdWeighting::kPaper46;

  /// Reference code: copies of one resampled parent share one proposal (a speed optimisation
  /// with no effect on results).
  bool reuse_parent_proposal = true;
  /// Random draws from one sequential stream (default) or keyed per (step, particle, purpose):
  /// common random numbers between versions of the filter (ci/GATES.md).
  DrawStreams draw_streams = DrawStreams::kSequential;
};

}  // namespace phdslam::filters
