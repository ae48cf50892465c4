#include "validation/runner/experiment/experiment_runner.h"

#include <algorithm>
#include <stdexcept>

#include "validation/runner/io/results_io.h"
#include "validation/runner/io/results_layout.h"
#include "validation/runner/registry/scenario_registry.h"
#include "validation/runner/registry/scenario_shorthands.h"

namespace phdslam::validation {
namespace {

// Prefixes an error with the experiment file's path, when the experiment has one.
[[noreturn]] void Rethrow(const Experiment& experiment, const std::invalid_argument& e) {
  if (experiment.source.is_object() && experiment.source.contains("path")) {
    throw std::invalid_argument(experiment.source.at("path").get<std::string>() + ": " + e.what());
  }
  throw e;
}

ScenarioOptions ToScenarioOptions(const Experiment& experiment) {
  ScenarioOptions options;
  options.data_dir = experiment.data_dir;
  options.steps = experiment.steps;
  for (const ScenarioShorthand& s : ScenarioShorthands()) {
    if (const auto member = ShorthandMember(s.key)) options.*s.value = experiment.*member;
  }
  options.settings = experiment.scenario_settings;
  return options;
}

// A shorthand (pd, clutter_rate) sets rows of the scenario's options; giving one of them as well
// would leave one of the two values unused.
void RequireShorthandsAlone(const Experiment& experiment) {
  for (const ScenarioShorthand& s : ScenarioShorthands()) {
    if (!SetsScenarioOption(experiment, s.key)) continue;
    for (const std::string& row : ShorthandRows(FindScenario(experiment.scenario), s.key)) {
      if (experiment.scenario_settings.contains(row)) {
        throw std::invalid_argument("scenario options '" + s.key + "' and '" + row + "' both set " +
                                    s.what + "; give one");
      }
    }
  }
}

// A deterministic estimator listed beside particle estimators, without particle counts of its
// own, runs at N = 1 only: the experiment's particle list is for the others.
void RunDeterministicAtOneParticle(const std::string& scenario, MonteCarloPlan& plan) {
  std::vector<bool> single;
  bool any_particle_estimator = false;
  for (const EstimatorSelection& s : plan.estimators) {
    single.push_back(s.particles.empty() &&
                     IsSingleParticleEstimator(s.entry, scenario, s.overrides));
    any_particle_estimator = any_particle_estimator || !single.back();
  }
  if (!any_particle_estimator) return;
  bool other_counts = false;  // a particle estimator runs with N != 1
  for (std::size_t i = 0; i < plan.estimators.size(); ++i) {
    const std::vector<int>& counts =
        plan.estimators[i].particles.empty() ? plan.particles : plan.estimators[i].particles;
    other_counts = other_counts || (!single[i] && counts != std::vector<int>{1});
  }
  for (std::size_t i = 0; i < plan.estimators.size(); ++i) {
    if (!single[i]) continue;
    plan.estimators[i].particles = {1};
    plan.estimators[i].held_at_one_particle = other_counts;
  }
}

// Throws when `runs` exceeds kMaxRuns.
void CheckRunTotal(double runs) {
  if (runs > kMaxRuns) {
    throw std::invalid_argument("the experiment has " + FormatNumber(runs) +
                                " runs (seeds x estimators x particle counts x sweep points), "
                                "more than the cap of " +
                                FormatNumber(kMaxRuns) + "; split it over several results folders");
  }
}

// The number of runs of a plan, from its lists (without listing the jobs); throws above kMaxRuns.
double CheckRunCount(const MonteCarloPlan& plan) {
  double per_seed = 0.0;
  for (const EstimatorSelection& s : plan.estimators) {
    per_seed +=
        static_cast<double>(s.particles.empty() ? plan.particles.size() : s.particles.size());
  }
  const double runs = per_seed * static_cast<double>(plan.seeds.size());
  CheckRunTotal(runs);
  return runs;
}

MonteCarloPlan BuildPlan(const Experiment& experiment, const std::vector<EstimatorEntry>& table) {
  RequireShorthandsAlone(experiment);
  MonteCarloPlan plan;
  plan.experiment = experiment.name;
  plan.particles = experiment.particles;
  plan.seeds = experiment.seeds;
  for (const ExperimentEstimator& e : experiment.estimators) {
    plan.estimators.push_back({FindEstimator(table, e.name), e.overrides, e.particles});
  }
  RunDeterministicAtOneParticle(experiment.scenario, plan);
  CheckRunCount(plan);
  plan.scenario = MakeScenarioSource(experiment.scenario, ToScenarioOptions(experiment));
  plan.experiment_file = experiment.source;
  return plan;
}

// The particle count an estimator of `x` is first run with (for checking its parameters).
int FirstParticleCount(const Experiment& x, const ExperimentEstimator& e) {
  const std::vector<int>& counts = e.particles.empty() ? x.particles : e.particles;
  return counts.empty() ? 1 : counts.front();
}

// A swept estimator parameter must be a parameter of some estimator it applies to; otherwise
// the sweep names something unknown (not particles, steps, a scenario option or a parameter).
void CheckEstimatorSweep(const Experiment& point, const ExperimentSweep& dimension,
                         const ScenarioEntry& scenario, const std::vector<EstimatorEntry>& table) {
  std::string errors;
  std::string value_error;  // an estimator that knows the parameter refused the value
  for (const ExperimentEstimator& e : point.estimators) {
    const EstimatorEntry& entry = FindEstimator(table, e.name);
    if (!entry.resolved_parameters) continue;
    EstimatorRequest request;
    request.name = e.name;
    request.particles = FirstParticleCount(point, e);
    request.scenario_name = point.scenario;
    request.overrides = e.overrides;
    try {
      entry.resolved_parameters(request);
      return;
    } catch (const std::invalid_argument& error) {
      const std::string what = error.what();
      errors += std::string(errors.empty() ? "" : "; ") + what;
      if (value_error.empty() && what.find("unknown parameter '") == std::string::npos) {
        value_error = what;
      }
    }
  }
  if (!value_error.empty()) {
    throw std::invalid_argument("sweep point " + dimension.parameter + " = " +
                                dimension.values.front().dump() + ": " + value_error);
  }
  std::string options;
  for (const ScenarioOptionHelp& o : scenario.option_keys) options += ", " + o.key;
  throw std::invalid_argument(
      "sweep parameter '" + dimension.parameter + "' (value " + dimension.values.front().dump() +
      ") is not particles, steps, pd, an option of scenario '" + scenario.name + "' (" +
      options.substr(2) + ") or a parameter of the estimators: " + errors);
}

std::vector<std::string> OptionKeys(const ScenarioEntry& scenario) {
  std::vector<std::string> keys;
  for (const ScenarioOptionHelp& o : scenario.option_keys) keys.push_back(o.key);
  return keys;
}

bool IsEstimatorSweep(const ExperimentSweep& d, const std::vector<std::string>& options) {
  const std::string& p = d.parameter;
  return p != kSweepParameterParticles && p != kSweepParameterSteps &&
         FindScenarioShorthand(p) == nullptr &&
         std::find(options.begin(), options.end(), p) == options.end();
}

std::vector<ExperimentPart> PlanSweep(const Experiment& experiment,
                                      const std::filesystem::path& out,
                                      const std::vector<EstimatorEntry>& table) {
  const ScenarioEntry& scenario = FindScenario(experiment.scenario);
  const std::vector<std::string> options = OptionKeys(scenario);
  CheckSweepNotSet(experiment, options);
  const std::vector<SweepPoint> points = SweepPoints(experiment.sweep);
  for (std::size_t i = 0; i < experiment.sweep.size(); ++i) {
    if (!IsEstimatorSweep(experiment.sweep[i], options)) continue;
    const SweepPoint& first = points.front();
    CheckEstimatorSweep(ApplySweepPoint(experiment, options, first), experiment.sweep[i], scenario,
                        table);
  }
  std::vector<ExperimentPart> parts;
  double runs = 0.0;
  for (const SweepPoint& point : points) {
    try {
      parts.push_back({point, out / SweepFolderName(experiment.sweep, point),
                       BuildPlan(ApplySweepPoint(experiment, options, point), table)});
      runs += CheckRunCount(parts.back().plan);
      CheckRunTotal(runs);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("sweep point " + DescribeSweepPoint(experiment.sweep, point) +
                                  ": " + e.what());
    }
  }
  return parts;
}

}  // namespace

std::vector<ExperimentPart> PlanExperiment(const Experiment& experiment,
                                           const std::filesystem::path& out,
                                           const std::vector<EstimatorEntry>& table) {
  try {
    if (experiment.sweep.empty()) return {{{}, out, BuildPlan(experiment, table)}};
    return PlanSweep(experiment, out, table);
  } catch (const std::invalid_argument& e) {
    Rethrow(experiment, e);
  }
}

ExperimentReport RunExperiment(const Experiment& experiment, const ExperimentSettings& settings,
                               const std::vector<EstimatorEntry>& table) {
  ExperimentReport report;
  report.parts = PlanExperiment(experiment, settings.out, table);
  std::vector<MonteCarloSettings> part_settings;
  std::size_t offset = 0;
  for (const ExperimentPart& part : report.parts) {
    MonteCarloSettings s;
    s.out = part.out;
    s.jobs = experiment.jobs.value_or(0);
    s.show_progress = settings.show_progress;
    s.report_failures = settings.report_failures;
    s.stop = settings.stop;
    s.metrics = settings.metrics;
    if (const auto c = FindScenario(part.plan.scenario.name).gospa_c) s.metrics.gospa_c = *c;
    s.shard = settings.shard;
    s.job_index_offset = offset;
    s.particles_trace = settings.particles_trace;
    s.map_ospa_trace = settings.map_ospa_trace;
    try {
      CheckMonteCarlo(part.plan, s);
    } catch (const std::invalid_argument& e) {
      if (part.sweep_point.empty()) Rethrow(experiment, e);
      Rethrow(experiment,
              std::invalid_argument("sweep point " +
                                    DescribeSweepPoint(experiment.sweep, part.sweep_point) + ": " +
                                    e.what()));
    }
    offset += PlanJobs(part.plan).size();
    part_settings.push_back(std::move(s));
  }
  for (std::size_t i = 0; i < report.parts.size(); ++i) {
    if (settings.stop != nullptr && settings.stop->load()) {
      report.interrupted = true;
      break;
    }
    report.reports.push_back(RunMonteCarlo(report.parts[i].plan, part_settings[i]));
    if (report.reports.back().interrupted) {
      report.interrupted = true;
      break;
    }
  }
  if (!experiment.sweep.empty()) WriteSweepFiles(settings.out, experiment.sweep);
  return report;
}

}  // namespace phdslam::validation
