#include "reference/ceres/batch_smoother.h"

#include <ceres/ceres.h>

#include <Eigen/LU>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "reference/ceres/factor_graph.h"
#include "reference/ceres/incremental_solve.h"
#include "reference/ceres/outlier_screening.h"
#include "reference/ceres/start_increments.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Landmarks farther than the sensor range plus this from the pose are not gated (m): a gate a
/// few metres wide cannot reach them.
constexpr double kGateDistanceMargin = 20.0;

/// Ceres stopped because a tolerance was met (not the iteration limit, not a failure).
bool SolveConverged(const ceres::Solver::Summary& summary) {
  return summary.termination_type == ceres::CONVERGENCE ||
         summary.termination_type == ceres::USER_SUCCESS;
}

std::unique_ptr<ceres::LossFunction> MakeLoss(const std::string& name, double scale) {
  if (name == "cauchy") return std::make_unique<ceres::CauchyLoss>(scale);
  if (name == "huber") return std::make_unique<ceres::HuberLoss>(scale);
  if (name == "none" || name.empty()) return nullptr;
  throw std::invalid_argument(
      "SmootherOptions.robust_loss: expected \"cauchy\", \"huber\" or "
      "\"none\", got \"" +
      name + "\"");
}

/// Turns per-measurement labels (any non-negative id, negative = none) into an association with
/// compact indices 0..M-1 in increasing label order, and the label of each index.
void CompactLabels(const std::vector<std::vector<int>>& labels, Association* association,
                   std::vector<int>* index_labels) {
  std::map<int, int> index_of;
  for (const auto& step : labels) {
    for (int l : step) {
      if (l >= 0) index_of.emplace(l, 0);
    }
  }
  index_labels->clear();
  for (auto& [label, index] : index_of) {
    index = static_cast<int>(index_labels->size());
    index_labels->push_back(label);
  }
  association->assign(labels.size(), {});
  for (std::size_t k = 0; k < labels.size(); ++k) {
    for (int l : labels[k]) {
      (*association)[k].push_back(l >= 0 ? index_of.at(l) : kUnassociated);
    }
  }
}

// The labels with at least `min_count` detections; the others become clutter (-1).
std::vector<std::vector<int>> LabelsSeenAtLeast(const std::vector<std::vector<int>>& labels,
                                                int min_count) {
  std::map<int, int> counts;
  for (const auto& step : labels) {
    for (int l : step) {
      if (l >= 0) ++counts[l];
    }
  }
  std::vector<std::vector<int>> kept = labels;
  for (auto& step : kept) {
    for (int& l : step) {
      if (l >= 0 && counts[l] < min_count) l = -1;
    }
  }
  return kept;
}

void CheckLabelShape(const datasets::Scenario& scenario,
                     const std::vector<std::vector<int>>& labels, const std::string& what) {
  if (labels.size() != scenario.steps.size()) {
    throw std::invalid_argument(what + ": expected " + std::to_string(scenario.steps.size()) +
                                " steps, got " + std::to_string(labels.size()));
  }
  for (std::size_t k = 0; k < labels.size(); ++k) {
    const std::size_t m = scenario.steps[k].data.measurements.size();
    if (labels[k].size() != m) {
      throw std::invalid_argument(what + "[" + std::to_string(k) + "]: expected " +
                                  std::to_string(m) + " labels (one per measurement), got " +
                                  std::to_string(labels[k].size()));
    }
  }
}

/// Landmark initial values: the inverse model at each landmark's first observation.
// The labels of options.filter_association (a filter's or the window's), checked against the
// scenario's shape, those with fewer than min_observations detections as clutter, compacted.
void CompactGivenLabels(const datasets::Scenario& scenario, const SmootherOptions& options,
                        Association* association, std::vector<int>* labels) {
  CheckLabelShape(scenario, options.filter_association, "SmootherOptions.filter_association");
  CompactLabels(LabelsSeenAtLeast(options.filter_association, options.min_observations),
                association, labels);
}

std::vector<Landmark> InitialLandmarks(const datasets::Scenario& scenario,
                                       const std::vector<Pose>& poses,
                                       const Association& association, std::size_t count) {
  std::vector<Landmark> landmarks(count, Landmark::Zero());
  std::vector<bool> set(count, false);
  for (std::size_t k = 0; k < association.size(); ++k) {
    for (std::size_t j = 0; j < association[k].size(); ++j) {
      const int i = association[k][j];
      if (i == kUnassociated || set[static_cast<std::size_t>(i)]) continue;
      landmarks[static_cast<std::size_t>(i)] =
          models::InverseMeasurement(poses[k], scenario.steps[k].data.measurements[j]);
      set[static_cast<std::size_t>(i)] = true;
    }
  }
  return landmarks;
}

/// Pose-known landmark covariances (sum Hm^T R^-1 Hm)^-1, used when ceres::Covariance is off or
/// fails.
std::vector<Mat2> PoseKnownLandmarkCovariances(const datasets::Scenario& scenario,
                                               const std::vector<Pose>& poses,
                                               const std::vector<Landmark>& landmarks,
                                               const Association& association) {
  const Mat2 r_inv = scenario.sensor.noise_cov.inverse();
  std::vector<Mat2> info(landmarks.size(), Mat2::Zero());
  for (std::size_t k = 0; k < association.size(); ++k) {
    for (int i : association[k]) {
      if (i == kUnassociated) continue;
      const auto li = static_cast<std::size_t>(i);
      if ((landmarks[li] - poses[k].head<2>()).squaredNorm() < 1e-18) continue;
      const Mat2 hm = models::MeasurementJacobians(poses[k], landmarks[li]).hm;
      info[li] += hm.transpose() * r_inv * hm;
    }
  }
  std::vector<Mat2> covs;
  for (const Mat2& m : info) {
    Mat2 p = m.inverse();
    Symmetrize(p);
    covs.push_back(p);
  }
  return covs;
}

}  // namespace

std::vector<OdometryIncrement> ScenarioOdometry(const datasets::Scenario& scenario,
                                                const OdometryNoiseFloor& floor) {
  const std::unique_ptr<models::MotionModel> model = scenario.MakeMotionModel();
  std::vector<OdometryIncrement> out;
  out.reserve(scenario.steps.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    try {
      out.push_back(
          ComposeStepOdometry(*model, scenario.steps[k].data, scenario.control_noise_cov, floor));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("scenario " + scenario.name + " step " + std::to_string(k) +
                                  ": " + e.what());
    }
  }
  return out;
}

std::vector<Pose> DeadReckoning(const datasets::Scenario& scenario,
                                const std::vector<OdometryIncrement>& increments) {
  std::vector<Pose> poses;
  poses.reserve(increments.size());
  Pose x = scenario.initial_pose;
  for (const OdometryIncrement& inc : increments) {
    if (inc.propagated) x = ComposeRelative(x, inc.delta);
    poses.push_back(x);
  }
  return poses;
}

void SmootherOptions::Validate() const {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("SmootherOptions." + what);
  };
  require(known_outlier_chi2 >= 0.0, "known_outlier_chi2: expected >= 0 (0: off)");
  require(max_iterations > 0, "max_iterations: expected > 0");
  require(std::isfinite(posterior.birth_log_weight),
          "posterior_birth_log_weight: expected a finite number");
  require(function_tolerance > 0.0, "function_tolerance: expected > 0");
  require(intermediate_function_tolerance > 0.0, "intermediate_function_tolerance: expected > 0");
  require(num_threads > 0, "num_threads: expected > 0");
  require(reassociation_rounds >= 0, "reassociation_rounds: expected >= 0");
  require(initial_pass_solve_steps >= 0, "initial_pass_solve_steps: expected >= 0");
  require(incremental_chunk_steps >= 1, "incremental_chunk_steps: expected >= 1");
  require(incremental_active_steps >= 0, "incremental_active_steps: expected >= 0");
  require(gate_chi2 > 0.0, "gate_chi2: expected > 0");
  require(incremental_jcbb_max_nodes >= 1, "incremental_jcbb_max_nodes: expected >= 1");
  require(incremental_jcbb_null_intensity >= 0.0,
          "incremental_jcbb_null_intensity: expected >= 0 (0: the most pairs)");
  require(incremental_new_landmark_intensity >= 0.0,
          "incremental_new_landmark_intensity: expected >= 0");
  require(incremental_static_point_chi2 >= 0.0,
          "incremental_static_point_chi2: expected >= 0 (0: off)");
  require(incremental_static_point_heading_std > 0.0,
          "incremental_static_point_heading_std: expected > 0");
  require(incremental_relocalisation_std >= 0.0,
          "incremental_relocalisation_std: expected >= 0 (0: off)");
  require(incremental_static_point_failures >= 1,
          "incremental_static_point_failures: expected >= 1");
  require(incremental_relocalisation_scans >= 2, "incremental_relocalisation_scans: expected >= 2");
  require(incremental_relocalisation_inlier_distance > 0.0,
          "incremental_relocalisation_inlier_distance: expected > 0");
  require(incremental_relocalisation_margin >= 1,
          "incremental_relocalisation_margin: expected >= 1");
  require(incremental_relocalisation_prior_weight >= 0.0,
          "incremental_relocalisation_prior_weight: expected >= 0");
  require(min_observations >= 1, "min_observations: expected >= 1");
  require(merge_position_std >= 0.0, "merge_position_std: expected >= 0");
  require(min_detection_ratio >= 0.0 && min_detection_ratio <= 1.0,
          "min_detection_ratio: expected in [0, 1]");
  require(robust_scale > 0.0, "robust_scale: expected > 0");
  require(filter_label_distance > 0.0, "filter_label_distance: expected > 0");
  require(start_particles >= 1, "start_particles: expected >= 1");
  require(start_from == StartTrajectory::kDeadReckoning || association != AssociationMode::kFilter,
          "start_from: the filter association starts from its own filter's trajectory");
  require(front_end == OwnFrontEnd::kPass || start_from == StartTrajectory::kDeadReckoning,
          "start_from: front_end window starts from the window's own trajectory");
  require(start_path == StartPath::kEstimate || start_from == StartTrajectory::kPhd3,
          "start_path: best-particle-path is a trajectory of the start_from filter run, "
          "which needs start_from: phd3");
  require(odometry_floor.position_std > 0.0 && odometry_floor.heading_std > 0.0,
          "odometry_floor: expected positive standard deviations");
  require(warm_start_floor.position_std > 0.0 && warm_start_floor.heading_std > 0.0,
          "warm_start_floor: expected positive standard deviations");
  MakeLoss(robust_loss, robust_scale);  // validates the name
}

BatchSmoother::BatchSmoother(SmootherOptions options) : options_(std::move(options)) {
  options_.Validate();
}

datasets::BatchResult BatchSmoother::Solve(const datasets::Scenario& scenario) {
  const Clock::time_point start = Clock::now();
  report_ = SmootherReport{};
  association_.clear();
  labels_.clear();
  datasets::BatchResult result;
  if (scenario.steps.empty()) return result;

  const std::vector<OdometryIncrement> increments =
      ScenarioOdometry(scenario, options_.odometry_floor);
  // Every solve but the last uses the looser warm-start floor when it is larger (README.md).
  const bool warm_start =
      options_.warm_start_floor.position_std > options_.odometry_floor.position_std;
  const std::vector<OdometryIncrement> loose_increments =
      warm_start ? ScenarioOdometry(scenario, options_.warm_start_floor) : increments;
  const bool control_space = options_.odometry_residual == OdometryResidual::kControlSpace;
  const OdometrySpec final_odometry{&increments, options_.odometry_floor, control_space};
  const OdometrySpec loose_odometry{
      &loose_increments, warm_start ? options_.warm_start_floor : options_.odometry_floor,
      control_space};
  std::vector<Pose> poses = DeadReckoning(scenario, increments);
  if (!options_.initial_poses.empty()) {
    if (options_.initial_poses.size() != scenario.steps.size()) {
      throw std::invalid_argument("SmootherOptions.initial_poses: expected " +
                                  std::to_string(scenario.steps.size()) + " poses, got " +
                                  std::to_string(options_.initial_poses.size()));
    }
    poses = options_.initial_poses;
  }
  std::vector<Landmark> landmarks;
  const std::unique_ptr<ceres::LossFunction> robust =
      MakeLoss(options_.robust_loss, options_.robust_scale);

  // Builds the graph on the current association and estimates, optimises it in place and
  // records the solve; returns the graph for the covariance step.
  const auto settings = [&](double function_tolerance) {
    SolveSettings st;
    st.max_iterations = options_.max_iterations;
    st.function_tolerance = function_tolerance;
    st.num_threads = options_.num_threads;
    st.linear_solver = options_.linear_solver;
    return st;
  };
  // Records one solve in the report; a solve that stopped before convergence is counted.
  const auto record = [&](const ceres::Solver::Summary& summary, double seconds) {
    report_.optimisation_seconds += seconds;
    report_.iterations += static_cast<int>(summary.iterations.size()) - 1;
    ++report_.solves;
    if (!SolveConverged(summary)) ++report_.unconverged_solves;
    report_.initial_cost = summary.initial_cost;
    report_.final_cost = summary.final_cost;
    report_.converged = SolveConverged(summary);
    report_.brief_reports.push_back(summary.BriefReport());
  };
  // Builds the graph on the current association and estimates, optimises it in place and
  // records the solve; returns the graph for the covariance step.
  const auto optimise = [&](const OdometrySpec& odometry, ceres::LossFunction* loss,
                            double function_tolerance) {
    const Clock::time_point t = Clock::now();
    auto graph =
        std::make_unique<FactorGraph>(scenario, odometry, association_, loss, &poses, &landmarks);
    const ceres::Solver::Summary summary = graph->Optimise(settings(function_tolerance));
    record(summary, SecondsSince(t));
    return graph;
  };
  // The incremental solve applies unless a start trajectory is given (README.md).
  const bool incremental = options_.initialisation == SmootherInitialisation::kIncremental &&
                           options_.initial_poses.empty();
  IncrementalSettings incremental_settings;
  incremental_settings.chunk_steps = static_cast<std::size_t>(options_.incremental_chunk_steps);
  incremental_settings.active_steps = static_cast<std::size_t>(options_.incremental_active_steps);
  incremental_settings.held_prior = options_.incremental_held_prior;
  incremental_settings.solve = settings(options_.intermediate_function_tolerance);

  // Known association: gross outliers (mislabelled detections) are left out of the final solves
  // (README.md, "Outliers in the known association").
  const bool screen_known =
      options_.association == AssociationMode::kKnown && options_.known_outlier_chi2 > 0.0;
  // Screening of the known association at the warm-started estimate (README.md, "Outliers in the
  // known association"). The screen uses a robust solve: at a squared-loss solve the outliers pull
  // the estimate until good measurements look like outliers too. A squared-loss estimate without
  // any measurement beyond the threshold is taken as it is (no further solve). Nothing is
  // screened at an estimate whose solve did not converge.
  const auto ScreenKnownAssociation = [&](bool robust_solved, ceres::LossFunction* robust_loss) {
    const double chi2 = options_.known_outlier_chi2;
    if (!robust_solved) {
      Association probe = association_;
      if (DropOutlierMeasurements(scenario, poses, landmarks, chi2, &probe) == 0) return;
      optimise(loose_odometry, robust_loss, options_.intermediate_function_tolerance);
    }
    if (!report_.converged) return;
    const int dropped = DropOutlierMeasurements(scenario, poses, landmarks, chi2, &association_);
    report_.outliers_dropped += dropped;
    if (dropped > 0) optimise(loose_odometry, nullptr, options_.intermediate_function_tolerance);
  };

  ceres::LossFunction* final_loss = nullptr;
  switch (options_.association) {
    case AssociationMode::kKnown: {
      std::vector<std::vector<int>> origins;
      for (const auto& step : scenario.steps) origins.push_back(step.origin);
      CheckLabelShape(scenario, origins, "known association (scenario.steps[k].origin)");
      CompactLabels(origins, &association_, &labels_);
      if (incremental) {
        // With outlier screening the chunk solves use the robust loss: a mislabelled detection
        // must not pull the growing trajectory before it is screened out.
        IncrementalSolve(scenario, loose_odometry, association_, labels_.size(),
                         screen_known ? robust.get() : nullptr, incremental_settings, record,
                         &poses, &landmarks);
      } else {
        landmarks = InitialLandmarks(scenario, poses, association_, labels_.size());
      }
      break;
    }
    case AssociationMode::kFilter: {
      // Labels with fewer than min_observations detections are taken as clutter, as a filter's
      // map estimate leaves out its weak (clutter-born) components.
      CompactGivenLabels(scenario, options_, &association_, &labels_);
      if (incremental) {
        IncrementalSolve(scenario, loose_odometry, association_, labels_.size(), robust.get(),
                         incremental_settings, record, &poses, &landmarks);
      } else {
        landmarks = InitialLandmarks(scenario, poses, association_, labels_.size());
      }
      final_loss = robust.get();
      break;
    }
    case AssociationMode::kUnknown: {
      AssociationOptions ao;
      std::vector<std::vector<bool>> moving_detections;  // left out of the rounds (ao.excluded)
      ao.gate_chi2 = options_.gate_chi2;
      ao.min_observations = options_.min_observations;
      ao.merge_position_std = options_.merge_position_std;
      ao.min_detection_ratio = options_.min_detection_ratio;
      ao.sensor = scenario.sensor;
      ao.measurement_cov = scenario.sensor.noise_cov;
      Clock::time_point t = Clock::now();
      if (options_.front_end == OwnFrontEnd::kWindow) {
        // Stage 1: the window's labels at its trajectory (initial_poses), the labels below
        // min_observations as clutter.
        if (options_.filter_association.empty()) {
          throw std::invalid_argument(
              "SmootherOptions.front_end: window needs the window's labels (filter_association)");
        }
        CompactGivenLabels(scenario, options_, &association_, &labels_);
        landmarks = InitialLandmarks(scenario, poses, association_, labels_.size());
      } else if (incremental) {
        // Stage 1: scan-to-map association along the incremental solve.
        IncrementalAssociationOptions io;
        io.gate.gate_chi2 = options_.gate_chi2;
        io.gate.max_landmark_distance = scenario.sensor.fov_range + kGateDistanceMargin;
        io.confirmation = {options_.min_observations, options_.min_detection_ratio};
        io.sensor = scenario.sensor;
        io.measurement_cov = scenario.sensor.noise_cov;
        io.squared_loss_marginals = options_.incremental_squared_marginals;
        io.delete_collapsed = options_.incremental_delete_collapsed;
        io.marginals_without_collapsed = options_.incremental_marginals_without_collapsed;
        io.skip_ambiguous = options_.incremental_skip_ambiguous;
        io.birth_outside_gates = options_.incremental_birth_outside_gates;
        io.pose_landmark_cross = options_.incremental_pose_landmark_cross;
        io.gate.new_landmark_intensity = options_.incremental_new_landmark_intensity;
        io.gate.assignment = options_.incremental_assignment;
        io.gate.jcbb_max_nodes = options_.incremental_jcbb_max_nodes;
        io.gate.jcbb_null_intensity = options_.incremental_jcbb_null_intensity;
        io.static_point_chi2 = options_.incremental_static_point_chi2;
        io.static_point_heading_std = options_.incremental_static_point_heading_std;
        io.static_point_failures = options_.incremental_static_point_failures;
        io.model_increments = &increments;
        io.relocalisation_position_std = options_.incremental_relocalisation_std;
        io.relocalisation_scans = options_.incremental_relocalisation_scans;
        io.relocalisation.inlier_distance = options_.incremental_relocalisation_inlier_distance;
        io.relocalisation.margin = options_.incremental_relocalisation_margin;
        io.relocalisation.prior_weight = options_.incremental_relocalisation_prior_weight;
        io.relocalisation_leave_ambiguous = options_.incremental_relocalisation_leave_ambiguous;
        AssociatedMap map =
            IncrementalAssociation(scenario, loose_odometry, robust.get(), incremental_settings, io,
                                   record, &report_.association_seconds);
        report_.moving_landmarks = map.moving;
        report_.relocalisations = map.relocalisations;
        report_.relocalisations_abandoned = map.relocalisations_abandoned;
        moving_detections = std::move(map.excluded);
        ao.excluded = &moving_detections;
        association_ = std::move(map.association);
        landmarks = std::move(map.landmarks);
        poses = std::move(map.poses);
      } else {
        // Stage 1: the sequential pass, with a smoothing solve of the steps done so far (confirmed
        // landmarks only) every initial_pass_solve_steps steps.
        // From a start trajectory the pass follows its relative motion instead of the odometry.
        SequentialAssociator associator(
            scenario,
            options_.initial_poses.empty()
                ? loose_increments
                : StartTrajectoryIncrements(scenario, options_.initial_poses, loose_increments),
            ao);
        const std::size_t chunk = options_.initial_pass_solve_steps > 0
                                      ? static_cast<std::size_t>(options_.initial_pass_solve_steps)
                                      : scenario.steps.size();
        for (std::size_t end = chunk; end < scenario.steps.size(); end += chunk) {
          associator.AdvanceTo(end);
          std::vector<int> track_ids;
          AssociatedMap partial = associator.Confirmed(&track_ids);
          report_.association_seconds += SecondsSince(t);
          association_ = std::move(partial.association);
          poses = std::move(partial.poses);
          landmarks = std::move(partial.landmarks);
          optimise(loose_odometry, robust.get(), options_.intermediate_function_tolerance);
          t = Clock::now();
          associator.Correct(poses, track_ids, landmarks);
        }
        associator.AdvanceTo(scenario.steps.size());
        AssociatedMap map = associator.Finish();
        report_.association_seconds += SecondsSince(t);
        association_ = std::move(map.association);
        landmarks = std::move(map.landmarks);
        poses = std::move(map.poses);
      }
      for (int round = 0; round < options_.reassociation_rounds; ++round) {
        optimise(loose_odometry, robust.get(), options_.intermediate_function_tolerance);
        t = Clock::now();
        AssociatedMap map = Reassociate(scenario, poses, landmarks, association_, ao);
        report_.association_seconds += SecondsSince(t);
        ++report_.reassociation_rounds;
        if (map.association == association_) {
          report_.association_converged = true;
          break;
        }
        association_ = std::move(map.association);
        landmarks = std::move(map.landmarks);
      }
      labels_.resize(landmarks.size());
      for (std::size_t i = 0; i < labels_.size(); ++i) labels_[i] = static_cast<int>(i);
      break;
    }
  }

  if (warm_start && options_.association != AssociationMode::kUnknown) {
    // After the incremental solve the estimate is close, and the robust loss safe, when the known
    // association is screened; from dead reckoning the squared loss.
    optimise(loose_odometry, screen_known && incremental ? robust.get() : final_loss,
             options_.intermediate_function_tolerance);
    if (screen_known) ScreenKnownAssociation(incremental, robust.get());
  }
  if (options_.association == AssociationMode::kFilter && options_.min_detection_ratio > 0.0) {
    // The filter's landmarks pass the unknown mode's detection-ratio test too, at the
    // warm-started trajectory: a clutter-born component the filter kept re-associating is seen
    // in only a few of the scans that cover it.
    AssociationOptions ao;
    ao.min_observations = options_.min_observations;
    ao.min_detection_ratio = options_.min_detection_ratio;
    ao.sensor = scenario.sensor;
    const std::vector<bool> keep = SupportedLandmarks(association_, landmarks, poses, ao);
    std::vector<int> new_index(landmarks.size(), kUnassociated);
    std::vector<Landmark> kept_landmarks;
    std::vector<int> kept_labels;
    for (std::size_t i = 0; i < landmarks.size(); ++i) {
      if (!keep[i]) continue;
      new_index[i] = static_cast<int>(kept_landmarks.size());
      kept_landmarks.push_back(landmarks[i]);
      kept_labels.push_back(labels_[i]);
    }
    for (auto& step : association_) {
      for (int& a : step) {
        if (a != kUnassociated) a = new_index[static_cast<std::size_t>(a)];
      }
    }
    landmarks = std::move(kept_landmarks);
    labels_ = std::move(kept_labels);
  }
  const std::unique_ptr<FactorGraph> graph =
      optimise(final_odometry, final_loss, options_.function_tolerance);

  result.pose_covs.assign(poses.size(), std::nullopt);
  std::vector<Mat2> landmark_covs;
  if (options_.compute_covariances) {
    const Clock::time_point t = Clock::now();
    report_.covariance_ok =
        graph->Covariances(options_.num_threads, &result.pose_covs, &landmark_covs);
    report_.covariance_seconds = SecondsSince(t);
    if (!report_.covariance_ok) result.pose_covs.assign(poses.size(), std::nullopt);
  }
  if (!report_.covariance_ok) {
    landmark_covs = PoseKnownLandmarkCovariances(scenario, poses, landmarks, association_);
  }

  report_.posterior = NegativeLogPosterior(scenario, final_odometry, poses, landmarks, association_,
                                           options_.posterior);
  report_.landmarks = landmarks.size();
  report_.associated_measurements = graph->residuals();
  result.poses = poses;
  result.map.means = landmarks;
  result.map.covs = std::move(landmark_covs);
  result.map.log_weights.assign(landmarks.size(), 0.0);
  result.iterations = report_.iterations;
  result.converged = report_.converged;
  // Only the own association's incremental pass re-localises, and only with the option on.
  if (incremental && options_.association == AssociationMode::kUnknown &&
      options_.incremental_relocalisation_std > 0.0) {
    result.relocalisations = report_.relocalisations;
  }
  result.neg_log_posterior = report_.posterior.Total();
  result.solve_seconds = SecondsSince(start);
  return result;
}

}  // namespace phdslam::reference
