// Runs an Experiment (from an experiment file or the command line): one Monte Carlo plan, or,
// for a sweep, one plan per sweep point into <out>/sweep-<parameter>-<value>.../ (sweep.h),
// followed by <out>/sweep.csv and <out>/sweep.json. Sharding applies to the experiment's whole
// job order.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "validation/runner/execution/monte_carlo.h"
#include "validation/runner/execution/shard.h"
#include "validation/runner/experiment/experiment_file.h"
#include "validation/runner/experiment/sweep.h"
#include "validation/runner/registry/estimator_registry.h"

namespace phdslam::validation {

/// Largest number of runs of one experiment (seeds x estimators x particle counts, summed over
/// the sweep points); larger studies are split over several results folders (e.g. by seeds).
inline constexpr double kMaxRuns = 2'000'000;

/// One Monte Carlo plan of an experiment and where its results go.
struct ExperimentPart {
  SweepPoint sweep_point;  ///< the swept parameters' values; empty without a sweep
  std::filesystem::path out;
  MonteCarloPlan plan;
};

/// The parts of an experiment, in order (sweep points in the order of SweepPoints). Estimators
/// are looked up in `table`; scenario options are resolved (and so validated) now. Throws
/// std::invalid_argument naming the experiment file (when there is one) for unknown estimators
/// or scenarios, bad options or swept values, an unknown sweep parameter, a swept parameter
/// that is also set, or more than kMaxRuns runs. A deterministic estimator (one that takes only
/// --particles 1) listed beside particle estimators, without particle counts of its own, runs at
/// N = 1 only.
std::vector<ExperimentPart> PlanExperiment(const Experiment& experiment,
                                           const std::filesystem::path& out,
                                           const std::vector<EstimatorEntry>& table);

struct ExperimentSettings {
  std::filesystem::path out;
  bool show_progress = true;
  bool report_failures = true;
  const std::atomic<bool>* stop = nullptr;
  Shard shard;
  bool particles_trace = false;
  bool map_ospa_trace = false;  ///< MonteCarloSettings::map_ospa_trace
  MetricSettings metrics;
};

struct ExperimentReport {
  std::vector<ExperimentPart> parts;
  std::vector<MonteCarloReport> reports;  ///< one per part that ran (fewer when interrupted)
  bool interrupted = false;
};

/// Checks every part (as RunMonteCarlo does) before running any, then runs them in order with
/// `experiment.jobs` worker threads. Sweeps end with WriteSweepFiles. Throws what
/// PlanExperiment and RunMonteCarlo throw.
ExperimentReport RunExperiment(const Experiment& experiment, const ExperimentSettings& settings,
                               const std::vector<EstimatorEntry>& table = EstimatorTable());

}  // namespace phdslam::validation
