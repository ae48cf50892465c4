#include "validation/runner/execution/run_estimator.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>

namespace phdslam::validation {
namespace {

using Clock = std::chrono::steady_clock;

double MillisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void RunOnline(const EstimatorEntry& entry, const EstimatorRequest& request,
               const datasets::Scenario& scenario,
               const std::function<void(std::size_t)>& on_steps_done, bool record_particles,
               bool record_maps, RunRecord& record) {
  if (!entry.HasFactory()) {
    throw std::logic_error("estimator '" + entry.name + "' has no online factory");
  }
  std::unique_ptr<filters::OnlineEstimator> estimator =
      entry.reads_truth ? entry.make_online_with_truth(request, scenario)
                        : entry.make_online(request);
  if (!estimator) {
    throw std::logic_error("estimator '" + entry.name + "' has no online factory");
  }
  const std::size_t n = scenario.steps.size();
  record.poses.reserve(n);
  record.pose_covs.reserve(n);
  record.diagnostics.reserve(n);
  record.associations.reserve(n);
  record.step_ms.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Clock::time_point start = Clock::now();
    filters::StepOutput out = estimator->Step(scenario.steps[k].data);
    const double ms = MillisecondsSince(start);
    record.poses.push_back(out.pose);
    record.pose_covs.push_back(out.pose_cov);
    record.pose_means_rb.push_back(out.pose_mean_rb);
    record.pose_covs_rb.push_back(out.pose_cov_rb);
    record.diagnostics.push_back(out.diag);
    record.associations.push_back(std::move(out.association));
    record.step_ms.push_back(ms);
    record.total_ms += ms;
    if (record_particles) record.particle_states.push_back(estimator->ParticleStates());
    if (record_maps) record.step_maps.push_back(estimator->Map().means);
    if (on_steps_done) on_steps_done(1);
  }
  const bool exposes_particles =
      std::any_of(record.particle_states.begin(), record.particle_states.end(),
                  [](const auto& states) { return !states.empty(); });
  if (!exposes_particles) record.particle_states.clear();
  record.final_map = estimator->Map();
  if (const auto* counter = dynamic_cast<const filters::SolveCounter*>(estimator.get())) {
    record.solves = counter->Solves();
  }
}

void RunBatch(const EstimatorEntry& entry, const EstimatorRequest& request,
              const datasets::Scenario& scenario,
              const std::function<void(std::size_t)>& on_steps_done, RunRecord& record) {
  if (!entry.make_batch) {
    throw std::logic_error("estimator '" + entry.name + "' has no batch factory");
  }
  std::unique_ptr<datasets::BatchEstimator> estimator = entry.make_batch(request);
  const Clock::time_point start = Clock::now();
  // The hidden origin labels reach only a batch estimator that declares it reads them.
  datasets::BatchResult result =
      entry.reads_truth ? estimator->Solve(scenario) : estimator->Solve(WithoutTruth(scenario));
  record.total_ms = MillisecondsSince(start);
  if (result.poses.size() != scenario.steps.size()) {
    throw std::runtime_error("estimator '" + entry.name + "' returned " +
                             std::to_string(result.poses.size()) + " poses for " +
                             std::to_string(scenario.steps.size()) + " steps");
  }
  record.poses = std::move(result.poses);
  if (!result.pose_covs.empty()) {
    if (result.pose_covs.size() != record.poses.size()) {
      throw std::runtime_error("estimator '" + entry.name + "' returned " +
                               std::to_string(result.pose_covs.size()) + " pose covariances for " +
                               std::to_string(record.poses.size()) + " poses");
    }
    record.pose_covs = std::move(result.pose_covs);
  }
  record.final_map = std::move(result.map);
  if (!entry.bound) record.solver_iterations = result.iterations;  // a bound solves nothing
  record.solver_converged = result.converged;
  record.relocalisations = result.relocalisations;
  record.neg_log_posterior = result.neg_log_posterior;
  if (on_steps_done) on_steps_done(record.poses.size());
}

}  // namespace

datasets::Scenario WithoutTruth(const datasets::Scenario& scenario) {
  datasets::Scenario public_part = scenario;
  for (datasets::ScenarioStep& step : public_part.steps) step.origin.clear();
  public_part.truth = {};
  return public_part;
}

RunRecord RunEstimator(const EstimatorEntry& entry, const EstimatorRequest& request,
                       const datasets::Scenario& scenario,
                       const std::function<void(std::size_t)>& on_steps_done, bool record_particles,
                       bool record_maps) {
  RunRecord record;
  record.estimator = entry.name;
  record.particles = request.particles;
  record.seed = scenario.seed;
  record.stream_seed = request.stream_seed;
  record.bound = entry.bound;
  record.particle_weights =
      !IsSingleParticleEstimator(entry, request.scenario_name, request.overrides);
  record.step_times.reserve(scenario.steps.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    if (scenario.steps[k].data.times.empty()) {
      throw std::runtime_error("scenario '" + scenario.name + "' step " + std::to_string(k) +
                               " has no time stamp");
    }
    record.step_times.push_back(scenario.StepTime(k));
  }
  if (entry.batch) {
    RunBatch(entry, request, scenario, on_steps_done, record);
  } else {
    RunOnline(entry, request, scenario, on_steps_done, record_particles, record_maps, record);
  }
  return record;
}

}  // namespace phdslam::validation
