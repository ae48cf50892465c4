// Per-run metrics computed from a RunRecord and its Scenario (docs/algorithms/metrics.md), and
// their metrics.json form.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "validation/metrics/association_accuracy.h"
#include "validation/runner/evaluation/error_moments.h"
#include "validation/runner/evaluation/map_ospa_trace.h"
#include "validation/runner/evaluation/run_record.h"

namespace phdslam::validation {

struct MetricSettings {
  double gospa_c = 20.0;               ///< m, GOSPA cut-off
  double gospa_p = 2.0;                ///< GOSPA order (alpha = 2)
  double gps_window_s = 0.025;         ///< GPS match window for real data
  double map_ospa_c = kMapOspaCutoff;  ///< m, cut-off of the per-step map OSPA
};

/// GOSPA of the final map against the true landmarks, with its decomposition. The three parts
/// are in p-th power units (m^p) and add up: gospa^p = localisation + missed + false_.
struct FinalMapGospa {
  double gospa = 0.0;         ///< m
  double localisation = 0.0;  ///< m^p, sum over assigned pairs of d^p
  double missed = 0.0;        ///< m^p, (c^p / 2) n_missed
  double false_ = 0.0;        ///< m^p, (c^p / 2) n_false
  int n_missed = 0;
  int n_false = 0;
};

struct RunMetrics {
  std::size_t steps = 0;
  /// Per-step position errors (m): against the true poses, or, for data with GPS only, against
  /// the GPS fix matched in time (unmatched steps left out).
  ErrorMoments position_m;
  /// Per-step heading errors (deg), the unwrapped difference; empty without true poses.
  ErrorMoments heading_deg;
  std::optional<FinalMapGospa> gospa;  ///< nullopt without a true map
  double gospa_c = 20.0;
  double gospa_p = 2.0;
  std::size_t map_size = 0;                   ///< components of the final map estimate
  std::optional<std::size_t> truth_map_size;  ///< true landmarks, when known
  /// Online estimators only (nullopt for batch estimators):
  std::optional<double> ess_pct;              ///< 100 * mean over steps of ESS / N
  std::optional<double> resampling_pct;       ///< 100 * fraction of steps that resampled
  std::optional<double> hypotheses_mean;      ///< mean over steps of StepDiagnostics::hypotheses
  std::optional<double> map_components_mean;  ///< mean over steps of map_components
  /// Pose NEES over the steps whose covariance is positive definite and whose truth is known.
  ErrorMoments pose_nees;
  /// Landmark NEES of the final map over the GOSPA-matched pairs (maps with covariances).
  ErrorMoments landmark_nees;
  /// Steps of pose_nees with NEES <= chi-square_3(0.95): the true pose inside the 95 % ellipsoid.
  std::size_t pose_coverage_inside = 0;
  /// Pose NEES with the Rao-Blackwellised mean and covariance (StepOutput::pose_mean_rb /
  /// pose_cov_rb), over the steps where that covariance is positive definite and truth is known.
  ErrorMoments pose_nees_rb;
  std::size_t pose_coverage_rb_inside = 0;  ///< steps of pose_nees_rb <= chi-square_3(0.95)
  /// Position NEES of the Rao-Blackwellised mean and (x, y) covariance against the matched GPS
  /// fix (data with GPS only; the GPS error itself is not in the covariance).
  ErrorMoments gps_nees_rb;
  std::size_t gps_coverage_rb_inside = 0;  ///< steps of gps_nees_rb <= chi-square_2(0.95)
  /// NIS of the estimate's associated measurements summed over every step, and their count
  /// (StepDiagnostics::nis_sum / nis_count); 2 per measurement for a consistent filter.
  double nis_sum = 0.0;
  std::size_t nis_count = 0;
  /// Data-association confusion counts over every step (metrics/association_accuracy.h, the
  /// landmark identity alone: no distance limit). nullopt for batch estimators and for scenarios
  /// without origin labels and a true map (real data). An online estimator that never reports an
  /// association has every measurement in `unreported` and NaN rates.
  std::optional<AssociationCounts> association;
  std::optional<std::size_t> gps_matched_steps;  ///< data with GPS only
  std::optional<std::size_t> solver_iterations;  ///< batch estimators: solver iterations
  /// Batch estimators: the final solve met its tolerance (false: stopped at the iteration limit
  /// or failed, so the estimate is not a converged solution).
  std::optional<bool> solver_converged;
  /// Online graph optimisers (filters::SolveCounter): solves run, and those that ended without
  /// convergence (reference/ceres/README.md says what is kept of them); nullopt for other
  /// estimators.
  std::optional<std::size_t> solves;
  std::optional<std::size_t> unconverged_solves;
  /// Batch estimators that re-localise (the Ceres smoother's own association with
  /// incremental_relocalisation_std > 0): re-localisations applied; nullopt for the others.
  std::optional<std::size_t> relocalisations;
  /// Batch estimators that score their solution (the Ceres smoother): the negative log posterior
  /// of its trajectory, map and association (nats, reference/ceres/association_posterior.h);
  /// nullopt for the others.
  std::optional<double> neg_log_posterior;
  ErrorMoments step_ms;  ///< wall time per step (online estimators)
  double total_ms = 0.0;
};

/// A run's metrics plus the per-step errors written to steps.csv.
struct RunEvaluation {
  RunMetrics metrics;
  std::vector<double> position_error_m;   ///< per step; NaN where unknown
  std::vector<double> heading_error_deg;  ///< per step; NaN where unknown
  /// Per step: pose NEES (e' P^-1 e, e = truth - estimate with the unwrapped heading
  /// difference); NaN without true poses, without a covariance, or when the covariance is not
  /// positive definite (zero or singular, e.g. at the first step of a particle filter).
  std::vector<double> pose_nees;
  /// Per step: pose NEES of the Rao-Blackwellised mean and covariance; NaN as for pose_nees.
  std::vector<double> pose_nees_rb;
  /// Per step (data with GPS only): (x, y) NEES of the Rao-Blackwellised mean and covariance
  /// against the matched GPS fix; NaN where unmatched or unavailable.
  std::vector<double> gps_nees_rb;
  /// Per step: the map OSPA of map_ospa_trace.h; empty unless the run recorded its maps.
  std::vector<double> map_ospa_m;
};

/// Evaluates a run against its scenario's truth. Throws std::invalid_argument when the record
/// does not have one pose per scenario step.
RunEvaluation EvaluateRun(const RunRecord& record, const datasets::Scenario& scenario,
                          const MetricSettings& settings = {});

/// Why the metrics of a run cannot be stored (an error statistic that overflowed to infinity or
/// is NaN, e.g. after the estimate diverged), or "" when they can. The runner records such a run
/// as failed with this reason instead of writing a metrics.json that later readers refuse.
std::string NonFiniteMetrics(const RunMetrics& m);

/// The first error-statistic field of a format-version-1 metrics.json that is null although it
/// must be a number: what older versions wrote for an overflowed error. "" when there is none (and
/// for every later version, which refuses to write such a run). Readers count such a run as failed.
std::string OverflowedMetricsField(const nlohmann::json& j);

/// The metrics.json key of the layout version, and the version this program writes. A file
/// without the key is version 1: the keys of version 2 (all but format_version), some of which it
/// may lack because it was written before they existed (the consistency keys, the association
/// counts, the solver keys: read as "none"). Version 2 requires those; version 3 adds
/// `relocalisations`, which files of versions 1 and 2 lack (read as "none"); version 4 adds
/// `neg_log_posterior`, which files of versions 1-3 lack (read as "none"). Version 4 requires
/// every key.
inline constexpr const char* kFormatVersionKey = "format_version";
inline constexpr int kMetricsFormatVersion = 4;

/// The format version of a metrics.json (1 without the key). Throws std::runtime_error naming
/// `source` and the version when it is not an integer or not one this program reads.
int MetricsFormatVersion(const nlohmann::json& j, const std::string& source);

/// metrics.json fields of RunMetrics (flat; "not available" is null), with format_version. The
/// keys and how each is written and read are one table (run_metrics_json.cc). Derived values
/// (RMSE, std, means, rates) are written for readers; RunMetricsFromJson reads back the
/// sufficient statistics.
nlohmann::json ToJson(const RunMetrics& m);
/// Throws std::runtime_error naming `source` and the field when a field is missing or mistyped,
/// or naming the version when the file's format_version is unknown (MetricsFormatVersion).
RunMetrics RunMetricsFromJson(const nlohmann::json& j, const std::string& source);

}  // namespace phdslam::validation
