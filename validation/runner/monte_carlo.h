// The Monte Carlo runner: runs every (estimator, particles, seed) job of a plan on worker threads
// and writes each finished run to <out>/runs/<estimator>-N<particles>/seed-<seed>/ (layout in
// validation/README.md). Results do not depend on the number of threads: each job builds its
// scenario and its estimator from its seeds only.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "datasets/scenario.h"
#include "validation/runner/estimator_registry.h"
#include "validation/runner/run_metrics.h"
#include "validation/runner/scenario_registry.h"
#include "validation/runner/summary.h"

namespace phdslam::validation {

struct EstimatorSelection {
  EstimatorEntry entry;  ///< usually a copy of an EstimatorTable() entry
  nlohmann::json overrides = nlohmann::json::object();
};

struct MonteCarloPlan {
  std::string experiment = "default";  ///< part of every stream seed (RunStreamSeed)
  ScenarioSource scenario;
  std::vector<EstimatorSelection> estimators;
  std::vector<int> particles;
  std::vector<std::uint64_t> seeds;
};

struct MonteCarloSettings {
  std::filesystem::path out;
  int jobs = 0;                 ///< worker threads; 0 = std::thread::hardware_concurrency()
  bool show_progress = true;    ///< progress line on stderr (drawn only on a terminal)
  bool report_failures = true;  ///< one stderr line per failed run as it fails
  const std::atomic<bool>* stop = nullptr;  ///< when set, no new run starts (Ctrl-C)
  MetricSettings metrics;
};

struct MonteCarloReport {
  std::size_t planned = 0;   ///< jobs in the plan
  std::size_t skipped = 0;   ///< already finished in <out> (resume)
  std::size_t finished = 0;  ///< computed and written by this call
  std::vector<FailedRun> failures;
  bool interrupted = false;  ///< the stop flag ended the call before every job ran
  double wall_seconds = 0.0;
  int jobs = 1;  ///< worker threads used
};

/// Runs the plan. Jobs are ordered seed by seed (all estimators and particle counts of the first
/// seed, then the next seed), so an interrupted call leaves comparable sets of seeds.
/// Before any run starts it throws std::invalid_argument for an empty or invalid plan (unknown
/// parameters, ...) and when <out> holds results made with different settings (experiment,
/// scenario options, estimator parameters). A failing run is recorded in its folder's
/// error.json, reported, and does not stop the others. Ends by writing summary.csv, runs.csv,
/// config.json and timing.json.
MonteCarloReport RunMonteCarlo(const MonteCarloPlan& plan, const MonteCarloSettings& settings);

/// The version string stored in config.json and metrics.json.
std::string ProgramVersion();

}  // namespace phdslam::validation
