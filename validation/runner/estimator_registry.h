// The table of estimators the runner and the command line know. Adding an estimator is one entry
// in EstimatorTable() (estimator_registry.cc).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "datasets/scenario.h"
#include "src/filters/estimator.h"

namespace phdslam::validation {

/// What an estimator factory receives for one Monte Carlo run.
struct EstimatorRequest {
  std::string name;
  int particles = 1;
  std::uint64_t stream_seed = 0;  ///< seed of the estimator's random stream (RunStreamSeed)
  /// The run's scenario. Online estimators build their EstimatorContext from its public part;
  /// the oracle and the smoother may read hidden labels through it.
  const datasets::Scenario* scenario = nullptr;
  /// The scenario's registered name; set even when `scenario` is not (parameter resolution
  /// happens before any scenario is built, and defaults depend on the scenario).
  std::string scenario_name;
  nlohmann::json overrides = nlohmann::json::object();  ///< parameter overrides (experiment/CLI)
};

struct EstimatorEntry {
  std::string name;
  std::string description;
  bool batch = false;  ///< true: make_batch is set; false: make_online is set
  std::function<std::unique_ptr<filters::OnlineEstimator>(const EstimatorRequest&)> make_online;
  std::function<std::unique_ptr<filters::BatchEstimator>(const EstimatorRequest&)> make_batch;
  /// All parameters after defaults and overrides; throws std::invalid_argument for an unknown
  /// parameter, a wrongly typed value or an unsupported particle count. Called when a run is
  /// planned, so bad requests fail before any run starts.
  std::function<nlohmann::json(const EstimatorRequest&)> resolved_parameters;
};

/// Every estimator, in the order `phdslam list` shows them.
const std::vector<EstimatorEntry>& EstimatorTable();

/// The entry called `name`; throws std::invalid_argument listing the known names.
const EstimatorEntry& FindEstimator(const std::string& name);

/// The same search over any table (tests use their own tables).
const EstimatorEntry& FindEstimator(const std::vector<EstimatorEntry>& table,
                                    const std::string& name);

/// Seed of an estimator's random stream for one run:
///   DeriveSeed(HashName(experiment), seed, DeriveSeed(HashName(estimator), particles)).
/// It depends only on these four values, so a run can be replayed alone and its result does not
/// depend on the number of worker threads or on which other runs are in the same invocation.
std::uint64_t RunStreamSeed(std::string_view experiment, std::uint64_t seed,
                            std::string_view estimator, int particles);

/// The request's scenario; throws naming the estimator when it has none.
const datasets::Scenario& RequireScenario(const EstimatorRequest& request);
/// Throws naming the estimator unless the request asks for exactly one particle.
void RequireSingleParticle(const EstimatorRequest& request);
/// The name of the request's scenario (from the scenario when given, else scenario_name).
const std::string& RequestScenarioName(const EstimatorRequest& request);

/// Entries of the optional external baselines; each list is empty when its library was not
/// built (the build picks the source file: reference_estimators_*.cc).
std::vector<EstimatorEntry> MrptEstimators();
std::vector<EstimatorEntry> CeresEstimators();

}  // namespace phdslam::validation
