#include "reference/ceres/batch_smoother.h"

#include <ceres/ceres.h>

#include <Eigen/LU>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "reference/ceres/odometry_factor.h"
#include "reference/ceres/range_bearing_factor.h"
#include "reference/ceres/velocity_odometry_factor.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
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

ceres::SparseLinearAlgebraLibraryType SparseLibrary() {
  return ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)
             ? ceres::SUITE_SPARSE
             : ceres::EIGEN_SPARSE;
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

/// How the odometry of a solve is modelled.
struct OdometrySpec {
  const std::vector<OdometryIncrement>* increments;  ///< pose-space increments with the floor
  OdometryNoiseFloor floor;
  bool control_space;  ///< VelocityOdometryFactor where it applies
};

/// The odometry factor of step k (linking pose k-1, or the anchor, to pose k).
ceres::CostFunction* MakeOdometryCost(const datasets::Scenario& scenario, std::size_t k,
                                      const OdometrySpec& spec) {
  const datasets::StepData& step = scenario.steps[k].data;
  if (spec.control_space && scenario.motion == datasets::MotionKind::kVelocity &&
      step.controls.size() == 1 && step.times[1] > step.times[0]) {
    return VelocityOdometryFactor::Create(step.controls[0], step.times[1] - step.times[0],
                                          WhiteningMatrix<2>(scenario.control_noise_cov),
                                          spec.floor.position_std);
  }
  const OdometryIncrement& inc = (*spec.increments)[k];
  return OdometryFactor::Create(inc.delta, WhiteningMatrix<3>(inc.covariance));
}

/// The factor graph of one solve. Parameter blocks point into `poses` and `landmarks`, which must
/// not be resized while the graph lives.
class FactorGraph {
 public:
  /// The graph of the first association.size() steps (all of `poses` when it has that many).
  FactorGraph(const datasets::Scenario& scenario, const OdometrySpec& odometry,
              const Association& association, ceres::LossFunction* loss, std::vector<Pose>* poses,
              std::vector<Landmark>* landmarks)
      : anchor_(scenario.initial_pose),
        steps_(association.size()),
        poses_(poses),
        landmarks_(landmarks) {
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_ = std::make_unique<ceres::Problem>(problem_options);
    if (steps_ == 0) return;
    for (std::size_t k = 0; k < steps_; ++k) problem_->AddParameterBlock((*poses)[k].data(), 3);
    for (Landmark& m : *landmarks) problem_->AddParameterBlock(m.data(), 2);

    // Gauge: the initial pose is known exactly. Without propagation at step 0, pose 0 is that
    // pose and is held constant; otherwise a constant anchor block holds it and step 0's
    // odometry links the anchor to pose 0.
    if ((*odometry.increments)[0].propagated) {
      problem_->AddParameterBlock(anchor_.data(), 3);
      problem_->SetParameterBlockConstant(anchor_.data());
      problem_->AddResidualBlock(MakeOdometryCost(scenario, 0, odometry), nullptr, anchor_.data(),
                                 (*poses)[0].data());
    } else {
      (*poses)[0] = scenario.initial_pose;
      problem_->SetParameterBlockConstant((*poses)[0].data());
      pose0_constant_ = true;
    }
    for (std::size_t k = 1; k < steps_; ++k) {
      problem_->AddResidualBlock(MakeOdometryCost(scenario, k, odometry), nullptr,
                                 (*poses)[k - 1].data(), (*poses)[k].data());
    }
    const Mat2 w = WhiteningMatrix<2>(scenario.sensor.noise_cov);
    for (std::size_t k = 0; k < association.size(); ++k) {
      for (std::size_t j = 0; j < association[k].size(); ++j) {
        const int i = association[k][j];
        if (i == kUnassociated) continue;
        problem_->AddResidualBlock(
            RangeBearingFactor::Create(scenario.steps[k].data.measurements[j], w), loss,
            (*poses)[k].data(), (*landmarks)[static_cast<std::size_t>(i)].data());
        ++residuals_;
      }
    }
  }

  ceres::Solver::Summary Optimise(const SmootherOptions& options, double function_tolerance) {
    ceres::Solver::Options o;
    // Sparse normal Cholesky (CHOLMOD, AMD ordering) by default: the graph is a long pose chain
    // with ~160 landmarks each seen from hundreds of poses. Eliminating the chain leaves a small
    // dense landmark front, while the Schur complement on the poses couples every pair of poses
    // that see a common landmark (a band several hundred poses wide). README.md has timings.
    o.linear_solver_type = options.linear_solver == SparseLinearSolver::kSparseSchur
                               ? ceres::SPARSE_SCHUR
                               : ceres::SPARSE_NORMAL_CHOLESKY;
    o.sparse_linear_algebra_library_type = SparseLibrary();
    if (options.linear_solver == SparseLinearSolver::kSparseSchur) {
      auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
      for (Landmark& m : *landmarks_) ordering->AddElementToGroup(m.data(), 0);
      for (std::size_t k = 0; k < steps_; ++k) ordering->AddElementToGroup((*poses_)[k].data(), 1);
      if (problem_->HasParameterBlock(anchor_.data())) {
        ordering->AddElementToGroup(anchor_.data(), 1);
      }
      o.linear_solver_ordering = ordering;
    }
    o.max_num_iterations = options.max_iterations;
    o.function_tolerance = function_tolerance;
    o.num_threads = options.num_threads;
    o.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(o, problem_.get(), &summary);
    return summary;
  }

  /// Marginal covariances of every pose and landmark block. SPARSE_QR (SuiteSparseQR when
  /// available) factors the Jacobian once and back-substitutes per column; DENSE_SVD would need
  /// the dense 12,000 x 12,000 information matrix of the paper scenario.
  bool Covariances(int num_threads, std::vector<std::optional<Mat3>>* pose_covs,
                   std::vector<Mat2>* landmark_covs) {
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::SPARSE_QR;
    co.sparse_linear_algebra_library_type = SparseLibrary();
    co.num_threads = num_threads;
    ceres::Covariance covariance(co);
    std::vector<std::pair<const double*, const double*>> blocks;
    for (std::size_t k = 0; k < steps_; ++k) {
      if (k == 0 && pose0_constant_) continue;
      blocks.emplace_back((*poses_)[k].data(), (*poses_)[k].data());
    }
    for (const Landmark& m : *landmarks_) blocks.emplace_back(m.data(), m.data());
    if (!covariance.Compute(blocks, problem_.get())) return false;
    pose_covs->assign(steps_, std::nullopt);
    for (std::size_t k = 0; k < steps_; ++k) {
      if (k == 0 && pose0_constant_) {
        (*pose_covs)[0] = Mat3::Zero();
        continue;
      }
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> c;
      if (!covariance.GetCovarianceBlock((*poses_)[k].data(), (*poses_)[k].data(), c.data())) {
        return false;
      }
      Mat3 p = c;
      Symmetrize(p);
      (*pose_covs)[k] = p;
    }
    landmark_covs->clear();
    for (const Landmark& m : *landmarks_) {
      Eigen::Matrix<double, 2, 2, Eigen::RowMajor> c;
      if (!covariance.GetCovarianceBlock(m.data(), m.data(), c.data())) return false;
      Mat2 p = c;
      Symmetrize(p);
      landmark_covs->push_back(p);
    }
    return true;
  }

  [[nodiscard]] std::size_t residuals() const { return residuals_; }

 private:
  Pose anchor_;
  std::size_t steps_;
  std::vector<Pose>* poses_;
  std::vector<Landmark>* landmarks_;
  std::unique_ptr<ceres::Problem> problem_;
  bool pose0_constant_ = false;
  std::size_t residuals_ = 0;
};

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
  require(max_iterations > 0, "max_iterations: expected > 0");
  require(function_tolerance > 0.0, "function_tolerance: expected > 0");
  require(intermediate_function_tolerance > 0.0, "intermediate_function_tolerance: expected > 0");
  require(num_threads > 0, "num_threads: expected > 0");
  require(reassociation_rounds >= 0, "reassociation_rounds: expected >= 0");
  require(initial_pass_solve_steps >= 0, "initial_pass_solve_steps: expected >= 0");
  require(gate_chi2 > 0.0, "gate_chi2: expected > 0");
  require(min_observations >= 1, "min_observations: expected >= 1");
  require(merge_position_std >= 0.0, "merge_position_std: expected >= 0");
  require(min_detection_ratio >= 0.0 && min_detection_ratio <= 1.0,
          "min_detection_ratio: expected in [0, 1]");
  require(robust_scale > 0.0, "robust_scale: expected > 0");
  require(filter_label_distance > 0.0, "filter_label_distance: expected > 0");
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
  const auto optimise = [&](const OdometrySpec& odometry, ceres::LossFunction* loss,
                            double function_tolerance) {
    const Clock::time_point t = Clock::now();
    auto graph =
        std::make_unique<FactorGraph>(scenario, odometry, association_, loss, &poses, &landmarks);
    const ceres::Solver::Summary summary = graph->Optimise(options_, function_tolerance);
    report_.optimisation_seconds += SecondsSince(t);
    report_.iterations += static_cast<int>(summary.iterations.size()) - 1;
    ++report_.solves;
    report_.initial_cost = summary.initial_cost;
    report_.final_cost = summary.final_cost;
    report_.brief_reports.push_back(summary.BriefReport());
    return graph;
  };

  ceres::LossFunction* final_loss = nullptr;
  switch (options_.association) {
    case AssociationMode::kKnown: {
      std::vector<std::vector<int>> origins;
      for (const auto& step : scenario.steps) origins.push_back(step.origin);
      CheckLabelShape(scenario, origins, "known association (scenario.steps[k].origin)");
      CompactLabels(origins, &association_, &labels_);
      landmarks = InitialLandmarks(scenario, poses, association_, labels_.size());
      break;
    }
    case AssociationMode::kFilter: {
      CheckLabelShape(scenario, options_.filter_association, "SmootherOptions.filter_association");
      // Labels with fewer than min_observations detections are taken as clutter, as a filter's
      // map estimate leaves out its weak (clutter-born) components.
      std::map<int, int> counts;
      for (const auto& step : options_.filter_association) {
        for (int l : step) {
          if (l >= 0) ++counts[l];
        }
      }
      std::vector<std::vector<int>> kept = options_.filter_association;
      for (auto& step : kept) {
        for (int& l : step) {
          if (l >= 0 && counts[l] < options_.min_observations) l = -1;
        }
      }
      CompactLabels(kept, &association_, &labels_);
      landmarks = InitialLandmarks(scenario, poses, association_, labels_.size());
      final_loss = robust.get();
      break;
    }
    case AssociationMode::kUnknown: {
      AssociationOptions ao;
      ao.gate_chi2 = options_.gate_chi2;
      ao.min_observations = options_.min_observations;
      ao.merge_position_std = options_.merge_position_std;
      ao.min_detection_ratio = options_.min_detection_ratio;
      ao.sensor = scenario.sensor;
      ao.measurement_cov = scenario.sensor.noise_cov;
      // Stage 1: the sequential pass, with a smoothing solve of the steps done so far (confirmed
      // landmarks only) every initial_pass_solve_steps steps.
      Clock::time_point t = Clock::now();
      SequentialAssociator associator(scenario, loose_increments, ao);
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
      for (int round = 0; round < options_.reassociation_rounds; ++round) {
        optimise(loose_odometry, robust.get(), options_.intermediate_function_tolerance);
        t = Clock::now();
        map = Reassociate(scenario, poses, landmarks, association_, ao);
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
    optimise(loose_odometry, final_loss, options_.intermediate_function_tolerance);
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

  report_.landmarks = landmarks.size();
  report_.associated_measurements = graph->residuals();
  result.poses = poses;
  result.map.means = landmarks;
  result.map.covs = std::move(landmark_covs);
  result.map.log_weights.assign(landmarks.size(), 0.0);
  result.iterations = report_.iterations;
  result.solve_seconds = SecondsSince(start);
  return result;
}

}  // namespace phdslam::reference
