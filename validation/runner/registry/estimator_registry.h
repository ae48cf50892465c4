// The table of estimators the runner and the command line know. Adding an estimator is its own
// source files plus one entry in EstimatorTable() (estimator_registry.cc); validation/README.md
// walks through an example.
//
// What an estimator may see is fixed by the factory it provides: `make_online` receives only the
// public context of the scenario (initial pose, models, noise), `make_online_with_truth` (the
// oracle) also the scenario with its hidden origin labels, and a batch estimator receives the
// scenario with its hidden labels removed unless the entry sets `reads_truth`.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "datasets/batch_estimator.h"
#include "datasets/scenario.h"
#include "src/core/parameter_table.h"
#include "src/filters/estimator.h"
#include "validation/runner/registry/scenario_defaults.h"

namespace phdslam::validation {

/// What an estimator factory receives for one Monte Carlo run.
struct EstimatorRequest {
  std::string name;
  int particles = 1;
  std::uint64_t stream_seed = 0;  ///< seed of the estimator's random stream (RunStreamSeed)
  /// The scenario's registered name (defaults depend on it: scenario_defaults.h).
  std::string scenario_name;
  nlohmann::json overrides = nlohmann::json::object();  ///< parameter overrides (experiment/CLI)
  /// The public part of the run's scenario; null while parameters are resolved (before any
  /// scenario is built).
  const filters::EstimatorContext* context = nullptr;
  /// Number of filter steps of the run's scenario; 0 when not known (`phdslam list`). The plan
  /// sets it for the entries bounded_by_run_length, which check those bounds then, and when
  /// they are built.
  std::size_t steps = 0;
  /// The scenario's nominal detection probability (NominalDetectionProbability of its resolved
  /// options); scenario defaults derive from it (scenario_defaults.h). Unset: none derived.
  std::optional<double> detection_probability = std::nullopt;
};

using OnlineFactory =
    std::function<std::unique_ptr<filters::OnlineEstimator>(const EstimatorRequest&)>;
using TruthReadingFactory = std::function<std::unique_ptr<filters::OnlineEstimator>(
    const EstimatorRequest&, const datasets::Scenario& with_truth)>;
using BatchFactory =
    std::function<std::unique_ptr<datasets::BatchEstimator>(const EstimatorRequest&)>;

struct EstimatorEntry {
  std::string name;
  std::string description;
  bool batch = false;  ///< true: make_batch is set
  /// Set for estimators that read the hidden truth (origin labels): the oracle, smoother-known.
  /// Online ones provide make_online_with_truth; batch ones receive the labels in Solve.
  bool reads_truth = false;
  /// Set for the posterior Cramer-Rao bounds (pcrb, pcrb-smoother: a batch entry that reads the
  /// truth): the evaluation puts the bound where other rows hold an error (run_metrics.h).
  bool bound = false;
  OnlineFactory make_online;
  TruthReadingFactory make_online_with_truth;
  BatchFactory make_batch;
  /// All parameters after defaults and overrides; throws std::invalid_argument for an unknown
  /// parameter, a wrongly typed value or an unsupported particle count. Called when a run is
  /// planned, so bad requests fail before any run starts.
  std::function<nlohmann::json(const EstimatorRequest&)> resolved_parameters;
  /// Set when a parameter is bounded by the run's length (window_length, solve_every,
  /// incremental_chunk_steps): the plan then gives resolved_parameters the length of the run,
  /// taken from the scenario when the data fix it (steps = 0), so that a bound is checked before
  /// any run or sweep point starts.
  bool bounded_by_run_length = false;
  /// The rows of the table that resolved_parameters reads `--set` with (key, accepted values,
  /// meaning), for `phdslam list` (estimator_parameter_list.h); empty: no parameters.
  std::vector<params::FieldDescription> parameters;

  /// True when the factory the entry's kind needs is set.
  [[nodiscard]] bool HasFactory() const {
    if (batch) return static_cast<bool>(make_batch);
    return reads_truth ? static_cast<bool>(make_online_with_truth) : static_cast<bool>(make_online);
  }
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

/// The request's public context; throws naming the estimator when it has none.
const filters::EstimatorContext& RequireContext(const EstimatorRequest& request);
/// The error of RequireSingleParticle: the estimator is deterministic and runs with one particle.
class SingleParticleOnly : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Throws SingleParticleOnly naming the estimator unless the request asks for exactly one
/// particle.
void RequireSingleParticle(const EstimatorRequest& request);

/// True when `entry` is deterministic (its parameters call RequireSingleParticle): it runs at
/// N = 1 whatever particle counts the experiment lists for the other estimators.
bool IsSingleParticleEstimator(const EstimatorEntry& entry, const std::string& scenario_name,
                               const nlohmann::json& overrides);
/// Throws naming the estimator when the request's scenario has no known measurement origins
/// (real data such as Victoria Park), for estimators that read the truth.
void RequireKnownOrigins(const EstimatorRequest& request);

/// The one parameter resolver: `defaults`, then the scenario's defaults for this estimator
/// (scenario_defaults.h), then the request's overrides, each checked by `table`; then the
/// request's particle count (>= 1) when Params has a `particles` member. Errors name the
/// estimator and the key.
template <class Params>
Params ResolveParameters(const EstimatorRequest& request,
                         const params::ParameterTable<Params>& table, Params defaults = {});

/// Entries of the optional external baselines; each list is empty when its library was not
/// built (the build picks the source file: reference_estimators_*.cc).
std::vector<EstimatorEntry> MrptEstimators();
std::vector<EstimatorEntry> CeresEstimators();
/// The posterior Cramer-Rao bounds, pcrb and pcrb-smoother (pcrb_entries.cc).
std::vector<EstimatorEntry> BoundEstimators();

template <class Params>
Params ResolveParameters(const EstimatorRequest& request,
                         const params::ParameterTable<Params>& table, Params defaults) {
  try {
    table.Apply(ScenarioParameterDefaults(request.scenario_name, request.name,
                                          request.detection_probability),
                defaults);
    const Params baseline = defaults;
    table.Apply(request.overrides, defaults);
    table.RequireUsed(request.overrides, baseline, defaults);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("estimator '" + request.name + "': " + e.what());
  }
  if constexpr (requires { defaults.particles; }) {
    if (request.particles < 1) {
      throw std::invalid_argument("estimator '" + request.name + "': --particles must be >= 1");
    }
    defaults.particles = request.particles;
  }
  return defaults;
}

}  // namespace phdslam::validation
