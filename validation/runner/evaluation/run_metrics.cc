#include "validation/runner/evaluation/run_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "src/core/gaussian.h"
#include "validation/metrics/gospa.h"
#include "validation/metrics/gps_position_error.h"
#include "validation/metrics/nees.h"
#include "validation/metrics/trajectory_error.h"
#include "validation/runner/evaluation/map_ospa_trace.h"

namespace phdslam::validation {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// NEES of one step, NaN when the covariance is absent, not positive definite or the value is
// not finite (a covariance that passes the Cholesky test can still be so close to singular that
// e'P^-1 e overflows: collapsed particles without resampling).
template <int N>
double StepNees(const Eigen::Matrix<double, N, 1>& truth, const Eigen::Matrix<double, N, 1>& mean,
                const std::optional<Eigen::Matrix<double, N, N>>& cov) {
  if (!cov || !CholeskyLower<N>(*cov)) return kNaN;
  try {
    double nees = 0.0;
    if constexpr (N == 3) {
      nees = PoseNees(truth, mean, *cov);
    } else {
      nees = LandmarkNees(truth, mean, *cov);
    }
    return std::isfinite(nees) ? nees : kNaN;
  } catch (const std::invalid_argument&) {
    return kNaN;  // not symmetric positive definite by the NEES test
  }
}

// The Rao-Blackwellised pose NEES against the true poses, with ellipsoid coverage.
void EvaluateRbNees(const RunRecord& record, const datasets::Scenario& scenario,
                    RunEvaluation& ev) {
  const std::size_t n = record.poses.size();
  const double threshold = EllipsoidThreshold(3);
  for (std::size_t k = 0; k < n && k < record.pose_covs_rb.size(); ++k) {
    if (!record.pose_means_rb[k] || !scenario.truth.PoseScored(k)) continue;
    const double nees =
        StepNees<3>(scenario.truth.poses[k], *record.pose_means_rb[k], record.pose_covs_rb[k]);
    if (std::isnan(nees)) continue;
    ev.pose_nees_rb[k] = nees;
    ev.metrics.pose_nees_rb.Add(nees);
    if (nees <= threshold) ++ev.metrics.pose_coverage_rb_inside;
  }
}

// The Rao-Blackwellised (x, y) NEES against the matched GPS fixes, with ellipse coverage.
void EvaluateGpsNees(const RunRecord& record, const datasets::Scenario& scenario,
                     const std::vector<int>& fix_index, RunEvaluation& ev) {
  const double threshold = EllipsoidThreshold(2);
  for (std::size_t k = 0; k < fix_index.size() && k < record.pose_covs_rb.size(); ++k) {
    if (fix_index[k] < 0 || !record.pose_means_rb[k] || !record.pose_covs_rb[k]) continue;
    const Vec2 gps = scenario.truth.gps[static_cast<std::size_t>(fix_index[k])].position;
    const std::optional<Mat2> cov = record.pose_covs_rb[k]->topLeftCorner<2, 2>().eval();
    const double nees = StepNees<2>(gps, record.pose_means_rb[k]->head<2>().eval(), cov);
    if (std::isnan(nees)) continue;
    ev.gps_nees_rb[k] = nees;
    ev.metrics.gps_nees_rb.Add(nees);
    if (nees <= threshold) ++ev.metrics.gps_coverage_rb_inside;
  }
}

void EvaluateTrajectory(const RunRecord& record, const datasets::Scenario& scenario,
                        const MetricSettings& settings, RunEvaluation& ev) {
  const std::size_t n = record.poses.size();
  const datasets::GroundTruth& truth = scenario.truth;
  if (truth.poses.size() == n && n > 0) {
    const PoseErrors errors = ComputePoseErrors(truth.poses, record.poses);
    for (std::size_t k = 0; k < n; ++k) {
      if (!truth.PoseScored(k)) continue;  // no truth at this step (a gap): NaN, not scored
      ev.position_error_m[k] = errors.position_m[k];
      ev.heading_error_deg[k] = errors.heading_rad[k] * kRadToDeg;
      ev.metrics.position_m.Add(ev.position_error_m[k]);
      ev.metrics.heading_deg.Add(ev.heading_error_deg[k]);
    }
    const double threshold = EllipsoidThreshold(3);
    for (std::size_t k = 0; k < n && k < record.pose_covs.size(); ++k) {
      if (!truth.PoseScored(k)) continue;
      if (!record.pose_covs[k] || !CholeskyLower<3>(*record.pose_covs[k])) continue;
      try {
        const double nees = PoseNees(truth.poses[k], record.poses[k], *record.pose_covs[k]);
        // A covariance that passes the Cholesky test can still be so close to singular that
        // e'P^-1 e overflows (collapsed particles without resampling): no NEES at that step.
        if (!std::isfinite(nees)) continue;
        ev.pose_nees[k] = nees;
        ev.metrics.pose_nees.Add(nees);
        if (nees <= threshold) ++ev.metrics.pose_coverage_inside;
      } catch (const std::invalid_argument&) {
        // Not symmetric positive definite by PoseNees' test: this step has no NEES.
      }
    }
    EvaluateRbNees(record, scenario, ev);
  } else if (!truth.gps.empty()) {
    const GpsErrors errors =
        ComputeGpsErrors(record.step_times, record.poses, truth.gps, settings.gps_window_s);
    ev.position_error_m = errors.error_m;
    for (double e : errors.error_m) ev.metrics.position_m.Add(e);
    ev.metrics.gps_matched_steps = errors.matched;
    EvaluateGpsNees(record, scenario, errors.fix_index, ev);
  }
}

// A bound's rows (RunRecord::bound): per step the root of the position block's trace and of the
// heading entry, so that the RMSE columns are the roots of their means over the scored steps;
// nothing else of the trajectory (NEES) has a meaning for a bound.
void EvaluateBound(const RunRecord& record, const datasets::Scenario& scenario, RunEvaluation& ev) {
  for (std::size_t k = 0; k < record.pose_covs.size(); ++k) {
    if (!scenario.truth.PoseScored(k) || !record.pose_covs[k]) continue;
    const Mat3& p = *record.pose_covs[k];
    ev.position_error_m[k] = std::sqrt(std::max(p(0, 0) + p(1, 1), 0.0));
    ev.heading_error_deg[k] = std::sqrt(std::max(p(2, 2), 0.0)) * kRadToDeg;
    ev.metrics.position_m.Add(ev.position_error_m[k]);
    ev.metrics.heading_deg.Add(ev.heading_error_deg[k]);
  }
}

void EvaluateMap(const RunRecord& record, const datasets::Scenario& scenario,
                 const MetricSettings& settings, RunMetrics& m) {
  m.map_size = record.final_map.size();
  m.gospa_c = settings.gospa_c;
  m.gospa_p = settings.gospa_p;
  if (scenario.truth.landmarks.empty()) return;
  m.truth_map_size = scenario.truth.landmarks.size();
  const GospaResult r =
      Gospa(scenario.truth.landmarks, record.final_map.means, settings.gospa_c, settings.gospa_p);
  FinalMapGospa g;
  g.gospa = r.gospa;
  g.localisation = r.localisation;
  g.missed = r.missed;
  g.false_ = r.false_;
  g.n_missed = r.n_missed;
  g.n_false = r.n_false;
  m.gospa = g;
  const filters::MapEstimate& map = record.final_map;
  if (map.covs.size() == map.size()) {
    try {
      for (double nees : MatchedLandmarkNees(scenario.truth.landmarks, map.means, map.covs, r)) {
        if (std::isfinite(nees)) m.landmark_nees.Add(nees);
      }
    } catch (const std::invalid_argument&) {
      // A matched component's covariance is not positive definite: no landmark NEES this run.
      m.landmark_nees = ErrorMoments{};
    }
  }
}

void EvaluateDiagnostics(const RunRecord& record, RunMetrics& m) {
  const std::size_t n = record.diagnostics.size();
  if (n == 0) return;
  double ess = 0.0;
  double resampled = 0.0;
  double hypotheses = 0.0;
  double components = 0.0;
  for (const filters::StepDiagnostics& d : record.diagnostics) {
    ess += d.ess / static_cast<double>(record.particles);
    resampled += d.resampled ? 1.0 : 0.0;
    hypotheses += d.hypotheses;
    components += d.map_components;
    m.nis_sum += d.nis_sum;
    m.nis_count += static_cast<std::size_t>(d.nis_count);
  }
  const double steps = static_cast<double>(n);
  if (record.particle_weights) {  // else left empty: no such quantity
    m.ess_pct = 100.0 * ess / steps;
    m.resampling_pct = 100.0 * resampled / steps;
  }
  m.hypotheses_mean = hypotheses / steps;
  m.map_components_mean = components / steps;
}

// Scores the reported associations against the hidden origin labels, when the scenario has them
// for every measurement and a true map.
void EvaluateAssociation(const RunRecord& record, const datasets::Scenario& scenario,
                         RunMetrics& m) {
  const std::size_t n = scenario.steps.size();
  if (record.associations.size() != n || scenario.truth.landmarks.empty()) return;
  for (const datasets::ScenarioStep& step : scenario.steps) {
    if (step.origin.size() != step.data.measurements.size()) return;
    for (int o : step.origin) {
      if (o < datasets::kClutter) return;
    }
  }
  AssociationCounts counts;
  std::vector<bool> seen_before;
  for (std::size_t k = 0; k < n; ++k) {
    try {
      AccumulateAssociation(scenario.steps[k].origin, record.associations[k],
                            scenario.truth.landmarks, seen_before,
                            std::numeric_limits<double>::infinity(), counts);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("run of '" + record.estimator + "' seed " +
                                  std::to_string(record.seed) + ", step " + std::to_string(k) +
                                  ": association: " + e.what());
    }
  }
  m.association = counts;
}

}  // namespace

RunEvaluation EvaluateRun(const RunRecord& record, const datasets::Scenario& scenario,
                          const MetricSettings& settings) {
  const std::size_t n = record.poses.size();
  if (n != scenario.steps.size() || record.step_times.size() != n) {
    throw std::invalid_argument(
        "run of '" + record.estimator + "' seed " + std::to_string(record.seed) + ": " +
        std::to_string(n) + " poses and " + std::to_string(record.step_times.size()) +
        " step times for " + std::to_string(scenario.steps.size()) + " scenario steps");
  }
  RunEvaluation ev;
  ev.metrics.steps = n;
  ev.position_error_m.assign(n, kNaN);
  ev.heading_error_deg.assign(n, kNaN);
  ev.pose_nees.assign(n, kNaN);
  ev.pose_nees_rb.assign(n, kNaN);
  ev.gps_nees_rb.assign(n, kNaN);
  if (record.bound) {
    EvaluateBound(record, scenario, ev);  // its map is the truth: no GOSPA
    ev.metrics.map_size = record.final_map.size();
    ev.metrics.truth_map_size = scenario.truth.landmarks.size();
  } else {
    EvaluateTrajectory(record, scenario, settings, ev);
    EvaluateMap(record, scenario, settings, ev.metrics);
  }
  EvaluateDiagnostics(record, ev.metrics);
  EvaluateAssociation(record, scenario, ev.metrics);
  for (double ms : record.step_ms) ev.metrics.step_ms.Add(ms);
  ev.map_ospa_m = MapOspaTrace(record, scenario, settings.map_ospa_c);
  ev.metrics.total_ms = record.total_ms;
  if (record.solves) {
    ev.metrics.solves = static_cast<std::size_t>(std::max(record.solves->solves, 0));
    ev.metrics.unconverged_solves =
        static_cast<std::size_t>(std::max(record.solves->unconverged, 0));
  }
  if (record.solver_iterations) {
    ev.metrics.solver_iterations = static_cast<std::size_t>(std::max(*record.solver_iterations, 0));
  }
  ev.metrics.solver_converged = record.solver_converged;
  if (record.relocalisations) {
    ev.metrics.relocalisations = static_cast<std::size_t>(std::max(*record.relocalisations, 0));
  }
  ev.metrics.neg_log_posterior = record.neg_log_posterior;
  return ev;
}

}  // namespace phdslam::validation
