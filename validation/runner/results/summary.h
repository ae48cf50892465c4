// Aggregation of finished Monte Carlo runs: reads every run's metrics.json under <out>/runs and
// writes <out>/summary.csv (one row per estimator and particle count) and <out>/runs.csv (one
// row per run). The columns are documented in validation/README.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "validation/runner/evaluation/error_moments.h"
#include "validation/runner/evaluation/run_metrics.h"

namespace phdslam::validation {

struct RunResult {
  std::string estimator;
  int particles = 1;
  std::uint64_t seed = 0;
  RunMetrics metrics;
  /// Per-step pose NEES (the `nees` column of steps.csv; NaN where empty), read only for runs
  /// with pose NEES values (metrics.pose_nees.count > 0); empty otherwise.
  std::vector<double> step_nees;
  /// The `nees_rb`, `nis_sum` and `nis_count` columns of steps.csv (NaN / 0 where empty), read
  /// only for runs with such values; empty otherwise.
  std::vector<double> step_nees_rb;
  std::vector<double> step_nis_sum;
  std::vector<double> step_nis_count;
};

/// Consistency of a group's pose estimates over the steps where every run has a pose NEES:
/// at each such step the NEES averaged over the runs, compared with the two-sided 95 % bounds
/// AveragedNeesBounds(3, runs). Steps where a run's covariance is absent, zero or singular are
/// left out.
struct GroupNees {
  double mean = 0.0;             ///< mean over the used steps of the run-averaged NEES
  double lower = 0.0;            ///< chi-square_{3 runs}(0.025) / runs
  double upper = 0.0;            ///< chi-square_{3 runs}(0.975) / runs
  double fraction_inside = 0.0;  ///< used steps with lower <= run-averaged NEES <= upper
  std::size_t steps = 0;         ///< steps used
  double median = 0.0;           ///< median over the used steps of the run-averaged NEES
};

/// Consistency of a group's NIS: at each step with associated measurements in some run, the
/// run-averaged NIS per measurement, sum_r nis_sum / sum_r nis_count (C measurements in all),
/// against the two-sided 95 % bounds chi-square_{2C}(0.025) / C and chi-square_{2C}(0.975) / C.
struct GroupNis {
  double mean = 0.0;    ///< NIS per measurement pooled over every step and run (2 expected)
  double median = 0.0;  ///< median over the used steps of the run-averaged NIS
  double fraction_inside = 0.0;  ///< used steps inside their bounds
  std::size_t steps = 0;         ///< steps used
};

struct FailedRun {
  std::string estimator;
  int particles = 1;
  std::uint64_t seed = 0;
  std::string error;
};

/// What a results folder holds, sorted by (estimator, particles, seed).
struct ResultsInventory {
  std::vector<RunResult> runs;    ///< finished runs (metrics.json present)
  std::vector<FailedRun> failed;  ///< runs with error.json and no metrics.json
};

/// One (estimator, particles) group: metrics pooled over its runs.
struct GroupSummary {
  std::string estimator;
  int particles = 1;
  std::size_t runs = 0;
  std::size_t failed_runs = 0;
  std::optional<double> steps;  ///< steps per run (their mean if runs differ)
  ErrorMoments position_m;      ///< every step of every run
  ErrorMoments heading_deg;
  ErrorMoments gospa_m;  ///< one value per run with a true map
  ErrorMoments gospa_localisation_mp;
  ErrorMoments gospa_missed_mp;
  ErrorMoments gospa_false_mp;
  ErrorMoments n_missed;
  ErrorMoments n_false;
  ErrorMoments map_size;
  std::optional<double> ess_pct;              ///< step-weighted over the runs
  std::optional<double> resampling_pct;       ///< step-weighted over the runs
  std::optional<double> hypotheses_mean;      ///< step-weighted over the runs
  std::optional<double> map_components_mean;  ///< step-weighted over the runs
  ErrorMoments pose_nees;
  ErrorMoments landmark_nees;
  /// Association counts summed over the runs that were scored; nullopt when none was.
  std::optional<AssociationCounts> association;
  ErrorMoments step_ms;
  ErrorMoments run_ms;             ///< total wall time per run
  ErrorMoments solver_iterations;  ///< batch estimators' solver iterations, one value per run
  std::size_t solver_runs = 0;     ///< runs that report whether their solve converged
  std::size_t solver_unconverged_runs = 0;  ///< of those, runs whose final solve did not
  std::optional<GroupNees> nees;            ///< nullopt when no step has a NEES in every run
  std::optional<GroupNees> nees_rb;         ///< the same for the Rao-Blackwellised pose NEES
  std::optional<GroupNis> nis;              ///< nullopt when no run reports NIS
  /// Fraction of steps (pooled over the runs) whose true pose lies inside the 95 % ellipsoid of
  /// the particle-spread / Rao-Blackwellised covariance, and of GPS fixes inside the RB (x, y)
  /// ellipse; nullopt without such steps.
  std::optional<double> coverage;
  std::optional<double> coverage_rb;
  std::optional<double> gps_coverage_rb;
  ErrorMoments pose_nees_rb;
  ErrorMoments gps_nees_rb;
};

/// GroupNees of runs' per-step NEES series (NaN = no NEES at that step); steps beyond the
/// shortest series are not used. nullopt when no runs are given or no step has a finite NEES in
/// every run.
std::optional<GroupNees> SummariseGroupNees(const std::vector<const std::vector<double>*>& runs);

/// GroupNis of runs' per-step NIS sums and counts (steps beyond a run's series count as 0 / 0).
/// nullopt when no step has a measurement in any run.
std::optional<GroupNis> SummariseGroupNis(const std::vector<const std::vector<double>*>& sums,
                                          const std::vector<const std::vector<double>*>& counts);

/// Reads <out>/runs/<estimator>-N<particles>/seed-<seed>/{metrics.json,error.json}, and the
/// `nees` column of steps.csv for runs with pose NEES values. Folders without either JSON file
/// (runs in progress or never started) are ignored. Throws std::runtime_error naming the file
/// when one cannot be parsed.
ResultsInventory ReadResults(const std::filesystem::path& out);

/// Groups the runs (and failures) by (estimator, particles), sorted by estimator then particles.
std::vector<GroupSummary> SummariseGroups(const ResultsInventory& inventory);

/// The CSV texts (header line plus rows).
std::string SummaryCsv(const std::vector<GroupSummary>& groups);
std::string RunsCsv(const std::vector<RunResult>& runs);

/// A fixed-width table of the summary's main columns, for the terminal.
std::string FormatSummaryTable(const std::vector<GroupSummary>& groups);

/// ReadResults + SummariseGroups, then writes <out>/summary.csv and <out>/runs.csv atomically.
std::vector<GroupSummary> WriteSummaryFiles(const std::filesystem::path& out);

}  // namespace phdslam::validation
