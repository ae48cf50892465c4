// Runs an Experiment (from an experiment file or the command line): one Monte Carlo plan, or,
// for a sweep, one plan per swept value into <out>/sweep-<parameter>-<value>/, followed by
// <out>/sweep.csv and <out>/sweep.json. Sharding applies to the experiment's whole job order.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "validation/runner/estimator_registry.h"
#include "validation/runner/experiment_file.h"
#include "validation/runner/monte_carlo.h"
#include "validation/runner/shard.h"

namespace phdslam::validation {

/// One Monte Carlo plan of an experiment and where its results go.
struct ExperimentPart {
  std::optional<double> sweep_value;  ///< nullopt without a sweep
  std::filesystem::path out;
  MonteCarloPlan plan;
};

/// The parts of an experiment, in order (sweep values in the order given). Estimators are looked
/// up in `table`; scenario options are resolved (and so validated) now. Throws
/// std::invalid_argument naming the experiment file (when there is one) for unknown estimators
/// or scenarios, bad options, or a swept parameter that is also set.
std::vector<ExperimentPart> PlanExperiment(const Experiment& experiment,
                                           const std::filesystem::path& out,
                                           const std::vector<EstimatorEntry>& table);

/// Folder of a sweep value: "sweep-<parameter>-<value>" (value as %.10g).
std::string SweepFolderName(const std::string& parameter, double value);

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

/// Writes <root>/sweep.json ({"parameter", "values", "folders"}) and <root>/sweep.csv: the
/// header of the first folder's summary.csv after a leading column named `parameter`, then the
/// rows of every folder's summary.csv (in the order of `values`) after the value (%.10g).
/// Folders without summary.csv are left out. Throws std::runtime_error when the summaries'
/// headers differ.
void WriteSweepFiles(const std::filesystem::path& root, const std::string& parameter,
                     const std::vector<double>& values);

}  // namespace phdslam::validation
