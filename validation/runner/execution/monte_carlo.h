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
#include "validation/runner/evaluation/run_metrics.h"
#include "validation/runner/execution/shard.h"
#include "validation/runner/registry/estimator_registry.h"
#include "validation/runner/registry/scenario_registry.h"
#include "validation/runner/results/summary.h"

namespace phdslam::validation {

struct EstimatorSelection {
  EstimatorEntry entry;  ///< usually a copy of an EstimatorTable() entry
  nlohmann::json overrides = nlohmann::json::object();
  /// Particle counts of this estimator; empty: the plan's.
  std::vector<int> particles = {};
  /// Set when the plan runs this deterministic estimator at N = 1 although the experiment lists
  /// other particle counts (for its other estimators), so that the run can say so.
  bool held_at_one_particle = false;
};

struct MonteCarloPlan {
  std::string experiment = "default";  ///< part of every stream seed (RunStreamSeed)
  ScenarioSource scenario;
  std::vector<EstimatorSelection> estimators;
  std::vector<int> particles;
  std::vector<std::uint64_t> seeds;
  /// Stored in config.json as "experiment_file" when set (the experiment file and how it was
  /// resolved); not part of any run's identity.
  nlohmann::json experiment_file = nullptr;
};

struct MonteCarloSettings {
  std::filesystem::path out;
  int jobs = 0;                 ///< worker threads; 0 = std::thread::hardware_concurrency()
  bool show_progress = true;    ///< progress line on stderr (drawn only on a terminal)
  bool report_failures = true;  ///< one stderr line per failed run as it fails
  const std::atomic<bool>* stop = nullptr;  ///< when set, no new run starts (Ctrl-C)
  MetricSettings metrics;
  /// Only the jobs whose index (job_index_offset + position in PlanJobs order) the shard
  /// contains are run; the others are counted in MonteCarloReport::outside_shard.
  Shard shard;
  std::size_t job_index_offset = 0;  ///< jobs of earlier parts of the experiment (sweeps)
  /// Write particles.csv (step,particle,x,y,log_weight) for estimators that expose particles.
  bool particles_trace = false;
  /// Record the map estimate after every step and write the per-step map OSPA (map_ospa_trace.h)
  /// as the last column of steps.csv, map_ospa_m.
  bool map_ospa_trace = false;
};

struct MonteCarloReport {
  std::size_t outside_shard = 0;  ///< jobs of the plan left to other shards
  std::size_t planned = 0;        ///< jobs of the plan in this shard (all jobs without --shard)
  std::size_t skipped = 0;        ///< already finished in <out> (resume)
  std::size_t finished = 0;       ///< computed and written by this call
  std::vector<FailedRun> failures;
  bool interrupted = false;  ///< the stop flag ended the call before every job ran
  double wall_seconds = 0.0;
  int jobs = 1;  ///< worker threads used
};

/// One job of a plan: estimator index into plan.estimators, particle count, seed.
struct PlannedJob {
  std::size_t estimator = 0;
  int particles = 1;
  std::uint64_t seed = 0;
};

/// The plan's jobs in their deterministic order: seed by seed (in the order given); within a
/// seed, estimator by estimator (in the order given); within an estimator, its particle counts
/// (in the order given). Shards select from this order.
std::vector<PlannedJob> PlanJobs(const MonteCarloPlan& plan);

/// Runs the plan. Jobs are ordered as PlanJobs (all estimators and particle counts of the first
/// seed, then the next seed), so an interrupted call leaves comparable sets of seeds.
/// Before any run starts it throws std::invalid_argument for an empty or invalid plan (unknown
/// parameters, ...) and when <out> holds results made with different settings (experiment,
/// scenario options, estimator parameters). A failing run is recorded in its folder's
/// error.json, reported, and does not stop the others. Ends by writing summary.csv, runs.csv,
/// config.json and timing.json.
MonteCarloReport RunMonteCarlo(const MonteCarloPlan& plan, const MonteCarloSettings& settings);

/// The checks RunMonteCarlo makes before any run starts (same exceptions), without running or
/// writing anything: lets a caller validate every part of an experiment (sweep values) first.
void CheckMonteCarlo(const MonteCarloPlan& plan, const MonteCarloSettings& settings);

/// The version string stored in config.json and metrics.json.
std::string ProgramVersion();

}  // namespace phdslam::validation
