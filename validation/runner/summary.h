// Aggregation of finished Monte Carlo runs: reads every run's metrics.json under <out>/runs and
// writes <out>/summary.csv (one row per estimator and particle count) and <out>/runs.csv (one
// row per run). The columns are documented in validation/README.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "validation/runner/error_moments.h"
#include "validation/runner/run_metrics.h"

namespace phdslam::validation {

struct RunResult {
  std::string estimator;
  int particles = 1;
  std::uint64_t seed = 0;
  RunMetrics metrics;
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
  ErrorMoments step_ms;
  ErrorMoments run_ms;  ///< total wall time per run
};

/// Reads <out>/runs/<estimator>-N<particles>/seed-<seed>/{metrics.json,error.json}. Folders
/// without either file (runs in progress or never started) are ignored. Throws
/// std::runtime_error naming the file when one cannot be parsed.
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
