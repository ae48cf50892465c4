#include "reference/ceres/fixed_lag_smoother.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "reference/ceres/landmark_covariance_floor.h"
#include "reference/ceres/linear_prior.h"
#include "reference/ceres/odometry_factor.h"
#include "reference/ceres/range_bearing_factor.h"
#include "reference/ceres/velocity_odometry_factor.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"
#include "src/models/velocity_motion_model.h"

namespace phdslam::reference {
namespace {

std::shared_ptr<ceres::LossFunction> MakeWindowLoss(const std::string& name, double scale) {
  if (name == "cauchy") return std::make_shared<ceres::CauchyLoss>(scale);
  if (name == "huber") return std::make_shared<ceres::HuberLoss>(scale);
  return nullptr;
}

ceres::SparseLinearAlgebraLibraryType WindowSparseLibrary() {
  return ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)
             ? ceres::SUITE_SPARSE
             : ceres::EIGEN_SPARSE;
}

/// Fallback pose covariance for gating when the window's information cannot be inverted.
Mat3 FallbackPoseCovariance() { return Vec3(1.0, 1.0, 0.01).asDiagonal(); }

}  // namespace

void WindowParams::Validate(std::size_t run_steps) const {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("window parameter " + what);
  };
  require(window_length >= 1, "window_length: expected >= 1 (poses kept in the window), got " +
                                  std::to_string(window_length));
  if (run_steps > 0) {
    require(static_cast<std::size_t>(window_length) <= run_steps,
            "window_length: " + std::to_string(window_length) + " is longer than the run (" +
                std::to_string(run_steps) + " steps)");
  }
  require(solve_every >= 1, "solve_every: expected >= 1, got " + std::to_string(solve_every));
  if (run_steps > 0) {
    require(static_cast<std::size_t>(solve_every) <= run_steps,
            "solve_every: " + std::to_string(solve_every) + " is longer than the run (" +
                std::to_string(run_steps) + " steps): nothing would be solved");
  }
  require(landmark_keep_steps >= 0, "landmark_keep_steps: expected >= 0");
  require(max_iterations >= 1, "max_iterations: expected >= 1");
  require(function_tolerance > 0.0, "function_tolerance: expected > 0");
  require(odometry_floor.position_std > 0.0 && odometry_floor.heading_std > 0.0,
          "odometry_floor: expected positive standard deviations");
  require(gate_chi2 > 0.0, "gate_chi2: expected > 0");
  require(jcbb_max_nodes >= 1, "jcbb_max_nodes: expected >= 1");
  require(jcbb_null_intensity >= 0.0, "jcbb_null_intensity: expected >= 0 (0: the most pairs)");
  require(confirm_detections >= 1, "confirm_detections: expected >= 1");
  require(confirm_ratio >= 0.0 && confirm_ratio <= 1.0, "confirm_ratio: expected in [0, 1]");
  require(robust_loss == "cauchy" || robust_loss == "huber" || robust_loss == "none",
          "robust_loss: expected \"cauchy\", \"huber\" or \"none\", got \"" + robust_loss + "\"");
  require(robust_scale > 0.0, "robust_scale: expected > 0");
  require(tentative_robust_scale > 0.0, "tentative_robust_scale: expected > 0");
  require(static_point_chi2 >= 0.0, "static_point_chi2: expected >= 0 (0: off)");
  require(static_point_heading_std > 0.0, "static_point_heading_std: expected > 0");
  require(static_point_failures >= 1, "static_point_failures: expected >= 1");
}

FixedLagSmoother::FixedLagSmoother(filters::EstimatorContext context, WindowParams params,
                                   std::vector<std::vector<int>> origins, std::size_t run_steps)
    : context_(std::move(context)), params_(std::move(params)), origins_(std::move(origins)) {
  params_.Validate(run_steps);
  if (!context_.motion) throw std::invalid_argument("FixedLagSmoother: no motion model");
  if (params_.known_association && run_steps > 0 && origins_.size() != run_steps) {
    throw std::invalid_argument("FixedLagSmoother: expected origin labels for " +
                                std::to_string(run_steps) + " steps, got " +
                                std::to_string(origins_.size()));
  }
  velocity_model_ =
      dynamic_cast<const models::VelocityMotionModel*>(context_.motion.get()) != nullptr;
  if (!params_.known_association) {
    loss_ = MakeWindowLoss(params_.robust_loss, params_.robust_scale);
    tentative_loss_ = std::make_shared<ceres::CauchyLoss>(params_.tentative_robust_scale);
  }
  measurement_whitening_ = WhiteningMatrix<2>(context_.sensor.noise_cov);
  anchor_ = context_.initial_pose;
}

void FixedLagSmoother::AddPose(const StepData& step) {
  const OdometryIncrement inc = ComposeStepOdometry(
      *context_.motion, step, context_.control_noise_cov, params_.odometry_floor);
  AdvanceStaticPointTracks(inc);
  WindowPose p;
  p.step = step_index_;
  if (step_index_ == 0 && !inc.propagated) {
    // The initial pose is known exactly: pose 0 is that pose, held constant.
    p.x = context_.initial_pose;
    p.constant = true;
    poses_.push_back(std::move(p));
    return;
  }
  double* previous = poses_.empty() ? anchor_.data() : poses_.back().x.data();
  p.x = ComposeRelative(Eigen::Map<const Pose>(previous), inc.delta);
  ceres::CostFunction* cost = nullptr;
  if (params_.odometry_residual == OdometryResidual::kControlSpace && velocity_model_ &&
      step.controls.size() == 1 && step.times[1] > step.times[0]) {
    cost = VelocityOdometryFactor::Create(step.controls[0], step.times[1] - step.times[0],
                                          WhiteningMatrix<2>(context_.control_noise_cov),
                                          params_.odometry_floor.position_std);
  } else {
    cost = OdometryFactor::Create(inc.delta, WhiteningMatrix<3>(inc.covariance));
  }
  poses_.push_back(std::move(p));
  poses_.back().odometry = GraphFactor{
      std::shared_ptr<ceres::CostFunction>(cost), nullptr, {previous, poses_.back().x.data()}};
}

void FixedLagSmoother::Observe(WindowPose& pose, int label, std::size_t j, const Measurement& z) {
  auto it = landmarks_.find(label);
  if (it == landmarks_.end()) {
    WindowLandmark lm;
    lm.mean = models::InverseMeasurement(pose.x, z);
    lm.first_step = pose.step;
    lm.support.expected = context_.sensor.DetectionProbability(pose.x, lm.mean);
    lm.status = params_.known_association ? LandmarkStatus::kConfirmed : LandmarkStatus::kTentative;
    if (params_.static_point_chi2 > 0.0) {
      lm.static_point.first = AnchorAt(z, context_.sensor.noise_cov);
      lm.static_point.latest = lm.static_point.first;
    }
    it = landmarks_.emplace(label, lm).first;
  } else if (!it->second.active) {
    // A marginalised landmark seen again: it re-enters with its marginal Gaussian as prior.
    WindowLandmark& lm = it->second;
    lm.active = true;
    const LinearPrior prior =
        GaussianPrior(lm.mean.data(), lm.mean, FlooredLandmarkCovariance(lm.cov));
    lm.reentry_prior =
        GraphFactor{std::shared_ptr<ceres::CostFunction>(LinearPriorFactor::Create(prior)),
                    nullptr,
                    {lm.mean.data()}};
  }
  WindowLandmark& lm = it->second;
  ++lm.support.detections;
  lm.last_step = pose.step;
  pose.observations.push_back(
      {label, j,
       GraphFactor{std::shared_ptr<ceres::CostFunction>(
                       RangeBearingFactor::Create(z, measurement_whitening_)),
                   lm.status == LandmarkStatus::kConfirmed ? loss_ : tentative_loss_,
                   {pose.x.data(), lm.mean.data()}}});
}

std::vector<int> FixedLagSmoother::OwnAssociation(const StepData& step) {
  const WindowPose& newest = poses_.back();
  std::vector<const double*> wanted;
  for (auto& [label, lm] : landmarks_) {
    if (lm.active) wanted.push_back(lm.mean.data());
  }
  // The newest pose's covariance and each window landmark's, with their cross-covariance.
  AnchoredCovariances covs;
  if (!newest.constant) {
    covs = AnchoredMarginalCovariances(WindowFactors(), ConstantBlocks(), newest.x.data(), wanted);
  }
  const bool have_covs = covs.marginal.size() == wanted.size() && covs.anchor.rows() == 3;
  Mat3 pose_cov = newest.constant ? Mat3::Zero() : FallbackPoseCovariance();
  if (!newest.constant && have_covs) pose_cov = covs.anchor;
  // Confirmed landmarks (in the window or marginalised) first, tentative ones on what is left.
  std::vector<MapLandmark> confirmed;
  std::vector<MapLandmark> tentative;
  std::vector<int> confirmed_labels;
  std::vector<int> tentative_labels;
  std::size_t next = 0;
  for (const auto& [label, lm] : landmarks_) {
    if (lm.moving) continue;
    MapLandmark m{lm.mean, lm.cov};
    if (params_.jcbb_null_intensity > 0.0) {
      m.detection_probability = context_.sensor.DetectionProbability(newest.x, lm.mean);
    }
    if (lm.active) {
      if (have_covs) {
        m.cov = covs.marginal[next];
        m.pose_cross = covs.cross[next];
      } else {
        m.cov = Mat2::Identity();
      }
      ++next;
    }
    const bool is_confirmed = lm.status == LandmarkStatus::kConfirmed;
    (is_confirmed ? confirmed : tentative).push_back(m);
    (is_confirmed ? confirmed_labels : tentative_labels).push_back(label);
  }
  ScanAssociationOptions gate;
  gate.gate_chi2 = params_.gate_chi2;
  gate.assignment = params_.assignment;
  gate.jcbb_max_nodes = params_.jcbb_max_nodes;
  gate.jcbb_null_intensity = params_.jcbb_null_intensity;
  const Mat2& r = context_.sensor.noise_cov;
  std::vector<int> labels(step.measurements.size(), -1);
  const ScanAssociation first =
      AssociateScan(newest.x, pose_cov, confirmed, step.measurements, r, gate);
  std::vector<std::size_t> rest;
  std::vector<Measurement> rest_z;
  for (std::size_t j = 0; j < labels.size(); ++j) {
    if (first.landmark[j] != kUnassociated) {
      labels[j] = confirmed_labels[static_cast<std::size_t>(first.landmark[j])];
    } else {
      rest.push_back(j);
      rest_z.push_back(step.measurements[j]);
    }
  }
  const ScanAssociation second = AssociateScan(newest.x, pose_cov, tentative, rest_z, r, gate);
  for (std::size_t k = 0; k < rest.size(); ++k) {
    if (second.landmark[k] != kUnassociated) {
      labels[rest[k]] = tentative_labels[static_cast<std::size_t>(second.landmark[k])];
    } else {
      labels[rest[k]] = next_label_++;
    }
  }
  return labels;
}

void FixedLagSmoother::AdvanceStaticPointTracks(const OdometryIncrement& increment) {
  if (params_.known_association || params_.static_point_chi2 <= 0.0) return;
  for (auto& [label, lm] : landmarks_) {
    if (!lm.moving) AdvanceTrack(increment, &lm.static_point);
  }
  const auto unseen = [&](const MovingTrack& t) {
    return step_index_ > t.last_step + static_cast<std::size_t>(params_.window_length);
  };
  std::erase_if(moving_tracks_, unseen);
  for (MovingTrack& t : moving_tracks_) {
    AdvanceAnchor(increment, &t.latest);
    if (t.first) AdvanceAnchor(increment, &*t.first);
  }
}

bool FixedLagSmoother::ContinuesMovingTrack(const Measurement& z) {
  const Mat2& r = context_.sensor.noise_cov;
  MovingTrack* best = nullptr;
  double best_chi2 = params_.static_point_chi2;
  for (MovingTrack& t : moving_tracks_) {
    const double chi2 = StaticPointChi2(t.latest, z, r);
    if (chi2 <= best_chi2) {
      best = &t;
      best_chi2 = chi2;
    }
  }
  if (best == nullptr) return false;
  best->latest = AnchorAt(z, r);
  best->last_step = step_index_;
  if (!best->first) {
    best->first = best->latest;
    best->taken = 1;
    return true;
  }
  if (++best->taken < params_.confirm_detections) return true;
  if (StaticPointChi2(*best->first, z, r) <= params_.static_point_chi2) {
    // Still where it was confirm_detections detections ago: a static point, no longer the track.
    moving_tracks_.erase(moving_tracks_.begin() + (best - moving_tracks_.data()));
    return false;
  }
  best->first = best->latest;
  best->taken = 1;
  return true;
}

bool FixedLagSmoother::HeldByPrior(const WindowLandmark& lm) const {
  return prior_ && std::find(prior_->blocks.begin(), prior_->blocks.end(), lm.mean.data()) !=
                       prior_->blocks.end();
}

void FixedLagSmoother::DropMovingObjects(const StepData& step, std::vector<int>& labels) {
  if (params_.static_point_chi2 <= 0.0) return;
  const StaticPointOptions check{params_.static_point_chi2, params_.static_point_heading_std,
                                 params_.static_point_failures};
  for (std::size_t j = 0; j < labels.size(); ++j) {
    if (labels[j] < 0) continue;
    const Measurement& z = step.measurements[j];
    const auto it = landmarks_.find(labels[j]);
    if (it == landmarks_.end()) {  // a new landmark, unless a moving object's detection
      if (ContinuesMovingTrack(z)) labels[j] = -1;
      continue;
    }
    WindowLandmark& lm = it->second;
    if (!MovingAfter(z, context_.sensor.noise_cov, check, &lm.static_point)) continue;
    ++report_.moving_landmarks;
    labels[j] = -1;
    MovingTrack track;
    track.latest = AnchorAt(z, context_.sensor.noise_cov);
    track.last_step = step_index_;
    moving_tracks_.push_back(track);
    // The marginal prior holds the landmark's block: it stays in the graph, but no longer takes
    // detections and leaves the map.
    if (HeldByPrior(lm)) {
      lm.moving = true;
    } else {
      DeleteLandmark(it->first);
      --report_.deleted_landmarks;  // counted as moving, not as an unconfirmed deletion
    }
  }
}

void FixedLagSmoother::CountExpectedDetections(const Pose& x) {
  for (auto& [label, lm] : landmarks_) {
    if (lm.active && lm.status == LandmarkStatus::kTentative) {
      lm.support.expected += context_.sensor.DetectionProbability(x, lm.mean);
    }
  }
}

void FixedLagSmoother::ClassifyTentative() {
  const ConfirmationOptions rule{params_.confirm_detections, params_.confirm_ratio};
  std::vector<int> deleted;
  for (auto& [label, lm] : landmarks_) {
    if (!lm.active || lm.status != LandmarkStatus::kTentative) continue;
    lm.status = ClassifyLandmark(lm.support, rule);
    if (lm.status == LandmarkStatus::kDeleted) deleted.push_back(label);
    if (lm.status == LandmarkStatus::kConfirmed) {
      for (WindowPose& p : poses_) {
        for (Observation& o : p.observations) {
          if (o.landmark == label) o.factor.loss = loss_;
        }
      }
    }
  }
  for (int label : deleted) DeleteLandmark(label);
}

void FixedLagSmoother::AddObservations(const StepData& step, filters::StepOutput& out) {
  std::vector<int> labels;
  if (params_.known_association) {
    if (step_index_ >= origins_.size() ||
        origins_[step_index_].size() != step.measurements.size()) {
      throw std::invalid_argument("FixedLagSmoother: step " + std::to_string(step_index_) +
                                  " has no origin label for every measurement");
    }
    labels = origins_[step_index_];
  } else {
    CountExpectedDetections(poses_.back().x);
    labels = OwnAssociation(step);
    DropMovingObjects(step, labels);
  }
  WindowPose& newest = poses_.back();
  label_log_.emplace_back(step.measurements.size(), -1);
  for (std::size_t j = 0; j < step.measurements.size(); ++j) {
    if (labels[j] < 0) continue;
    const bool existed = landmarks_.count(labels[j]) > 0;
    // A landmark on the pose has no bearing: such a detection cannot be used.
    if (existed && (landmarks_.at(labels[j]).mean - newest.x.head<2>()).squaredNorm() < 1e-18) {
      continue;
    }
    Observe(newest, labels[j], j, step.measurements[j]);
    label_log_.back()[j] = labels[j];
  }
  if (!params_.known_association) ClassifyTentative();
  out.association.assign(step.measurements.size(),
                         Landmark::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (const Observation& o : newest.observations) {
    const WindowLandmark& lm = landmarks_.at(o.landmark);
    if (params_.known_association || lm.support.detections > 1) {
      out.association[o.measurement] = lm.mean;
    }
  }
}

std::vector<const GraphFactor*> FixedLagSmoother::WindowFactors() const {
  std::vector<const GraphFactor*> factors;
  if (prior_) factors.push_back(&*prior_);
  for (const WindowPose& p : poses_) {
    if (p.odometry) factors.push_back(&*p.odometry);
    for (const Observation& o : p.observations) factors.push_back(&o.factor);
  }
  for (const auto& [label, lm] : landmarks_) {
    if (lm.active && lm.reentry_prior) factors.push_back(&*lm.reentry_prior);
  }
  return factors;
}

std::set<const double*> FixedLagSmoother::ConstantBlocks() const {
  std::set<const double*> constant{anchor_.data()};
  for (const WindowPose& p : poses_) {
    if (p.constant) constant.insert(p.x.data());
  }
  return constant;
}

void FixedLagSmoother::Solve() {
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  for (const GraphFactor* f : WindowFactors()) {
    problem.AddResidualBlock(f->cost.get(), f->loss.get(), f->blocks);
  }
  if (problem.NumResidualBlocks() == 0) return;
  for (const double* b : ConstantBlocks()) {
    auto* block = const_cast<double*>(b);  // NOLINT(cppcoreguidelines-pro-type-const-cast)
    if (problem.HasParameterBlock(block)) problem.SetParameterBlockConstant(block);
  }
  // Values before the solve, restored when the solver fails.
  std::vector<Pose> poses_before;
  for (const WindowPose& p : poses_) poses_before.push_back(p.x);
  std::map<int, Landmark> landmarks_before;
  for (const auto& [label, lm] : landmarks_) {
    if (lm.active) landmarks_before.emplace(label, lm.mean);
  }

  ceres::Solver::Options o;
  o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  o.sparse_linear_algebra_library_type = WindowSparseLibrary();
  o.max_num_iterations = params_.max_iterations;
  o.function_tolerance = params_.function_tolerance;
  o.num_threads = 1;
  o.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);
  ++report_.solves;
  report_.iterations += static_cast<int>(summary.iterations.size());
  if (summary.termination_type == ceres::CONVERGENCE) return;
  ++report_.unconverged_solves;
  if (summary.termination_type == ceres::NO_CONVERGENCE && summary.IsSolutionUsable()) return;
  for (std::size_t i = 0; i < poses_.size(); ++i) poses_[i].x = poses_before[i];
  for (const auto& [label, mean] : landmarks_before) landmarks_.at(label).mean = mean;
}

int FixedLagSmoother::RejectOutliers() {
  int rejected = 0;
  for (WindowPose& p : poses_) {
    std::erase_if(p.observations, [&](const Observation& o) {
      WindowLandmark& lm = landmarks_.at(o.landmark);
      if (lm.status != LandmarkStatus::kConfirmed) return false;
      Vec2 r;
      const std::array<const double*, 2> blocks{p.x.data(), lm.mean.data()};
      if (!o.factor.cost->Evaluate(blocks.data(), r.data(), nullptr)) return false;
      if (r.squaredNorm() < params_.gate_chi2) return false;
      --lm.support.detections;
      ++rejected;
      label_log_[p.step][o.measurement] = -1;
      return true;
    });
  }
  report_.rejected_detections += rejected;
  return rejected;
}

bool FixedLagSmoother::KeepTimeOver(const WindowLandmark& lm) const {
  return poses_.back().step >= lm.last_step + static_cast<std::size_t>(params_.landmark_keep_steps);
}

bool FixedLagSmoother::ObservedAfterOldest(int label) const {
  for (std::size_t i = 1; i < poses_.size(); ++i) {
    for (const Observation& o : poses_[i].observations) {
      if (o.landmark == label) return true;
    }
  }
  return false;
}

void FixedLagSmoother::DeleteLandmark(int label) {
  for (WindowPose& p : poses_) {
    std::erase_if(p.observations, [label](const Observation& o) { return o.landmark == label; });
  }
  landmarks_.erase(label);
  ++report_.deleted_landmarks;
}

void FixedLagSmoother::MarginaliseOldest() {
  // Tentative landmarks first seen from the leaving pose and still unconfirmed are deleted.
  if (!params_.known_association) {
    std::vector<int> unconfirmed;
    for (const Observation& o : poses_.front().observations) {
      const WindowLandmark& lm = landmarks_.at(o.landmark);
      if (lm.status != LandmarkStatus::kConfirmed && lm.first_step == poses_.front().step) {
        unconfirmed.push_back(o.landmark);
      }
    }
    for (int label : unconfirmed) DeleteLandmark(label);
  }
  WindowPose& old = poses_.front();
  std::vector<int> leaving;
  for (const auto& [label, lm] : landmarks_) {
    if (lm.active && !ObservedAfterOldest(label) && KeepTimeOver(lm)) leaving.push_back(label);
  }
  const std::set<const double*> constant = ConstantBlocks();
  std::vector<double*> leaving_blocks;
  leaving_blocks.reserve(leaving.size());
  for (int label : leaving) leaving_blocks.push_back(landmarks_.at(label).mean.data());
  std::vector<Eigen::MatrixXd> covs;
  if (!leaving_blocks.empty()) {
    covs = MarginalCovariances(WindowFactors(), constant,
                               {leaving_blocks.begin(), leaving_blocks.end()});
  }

  std::vector<const GraphFactor*> factors;
  if (prior_) factors.push_back(&*prior_);
  if (old.odometry) factors.push_back(&*old.odometry);
  if (poses_.size() > 1 && poses_[1].odometry) factors.push_back(&*poses_[1].odometry);
  for (const Observation& o : old.observations) factors.push_back(&o.factor);
  for (int label : leaving) {
    const WindowLandmark& lm = landmarks_.at(label);
    if (lm.reentry_prior) factors.push_back(&*lm.reentry_prior);
  }
  std::vector<double*> marginalised = leaving_blocks;
  marginalised.push_back(old.x.data());
  const LinearPrior prior = Marginalize(factors, marginalised, constant, fixed_points_);

  for (std::size_t i = 0; i < leaving.size(); ++i) {
    WindowLandmark& lm = landmarks_.at(leaving[i]);
    if (covs.size() == leaving.size()) {
      lm.cov = covs[i];
    } else {
      // The window's information could not be inverted: the landmark's conditional covariance
      // given the rest (its own 2x2 information block), an optimistic stand-in.
      std::vector<const GraphFactor*> own;
      for (const GraphFactor* f : factors) {
        if (std::find(f->blocks.begin(), f->blocks.end(), lm.mean.data()) != f->blocks.end()) {
          own.push_back(f);
        }
      }
      const DenseSystem s = Linearize(own, {lm.mean.data()}, fixed_points_);
      lm.cov = s.h.rows() == 2 ? Mat2(s.h.inverse()) : Mat2(Mat2::Identity());
    }
    lm.cov = FlooredLandmarkCovariance(lm.cov);
    lm.active = false;
    lm.reentry_prior.reset();
  }
  if (poses_.size() > 1) poses_[1].odometry.reset();
  poses_.pop_front();
  fixed_points_.clear();
  if (prior.Empty()) {
    prior_.reset();
  } else {
    for (std::size_t i = 0; i < prior.blocks.size(); ++i) {
      fixed_points_[prior.blocks[i]] = prior.linearization_points[i];
    }
    prior_ = GraphFactor{std::shared_ptr<ceres::CostFunction>(LinearPriorFactor::Create(prior)),
                         nullptr, prior.blocks};
  }
  ++report_.marginalised_poses;
}

filters::StepOutput FixedLagSmoother::Step(const StepData& step) {
  filters::StepOutput out;
  AddPose(step);
  AddObservations(step, out);
  ++steps_since_solve_;
  if (steps_since_solve_ >= params_.solve_every) {
    steps_since_solve_ = 0;
    Solve();
    if (!params_.known_association && params_.reject_outliers && RejectOutliers() > 0) Solve();
    while (poses_.size() > static_cast<std::size_t>(params_.window_length)) MarginaliseOldest();
  }
  out.pose = poses_.back().x;
  // The associated landmarks' means after the solve.
  for (std::size_t j = 0; j < out.association.size(); ++j) {
    if (!out.association[j].allFinite()) continue;
    for (const Observation& o : poses_.back().observations) {
      if (o.measurement == j) out.association[j] = landmarks_.at(o.landmark).mean;
    }
  }
  int active = 0;
  for (const auto& [label, lm] : landmarks_) active += lm.active ? 1 : 0;
  out.diag.map_components = active;
  ++step_index_;
  return out;
}

filters::MapEstimate FixedLagSmoother::Map() const {
  std::vector<const double*> wanted;
  for (const auto& [label, lm] : landmarks_) {
    if (lm.active && lm.status == LandmarkStatus::kConfirmed && !lm.moving) {
      wanted.push_back(lm.mean.data());
    }
  }
  std::vector<Eigen::MatrixXd> covs;
  if (!wanted.empty()) {
    covs = MarginalCovariances(WindowFactors(), ConstantBlocks(), wanted);
  }
  filters::MapEstimate map;
  std::size_t next = 0;
  for (const auto& [label, lm] : landmarks_) {
    if (lm.status != LandmarkStatus::kConfirmed || lm.moving) continue;
    map.means.push_back(lm.mean);
    if (lm.active) {
      map.covs.push_back(covs.size() == wanted.size() ? Mat2(covs[next]) : Mat2(Mat2::Identity()));
      ++next;
    } else {
      map.covs.push_back(lm.cov);
    }
    map.log_weights.push_back(0.0);
  }
  return map;
}

std::vector<std::vector<int>> FixedLagSmoother::FinalLabels() const {
  std::vector<std::vector<int>> labels = label_log_;
  for (std::vector<int>& step : labels) {
    for (int& label : step) {
      const auto it = landmarks_.find(label);
      const bool kept = it != landmarks_.end() && it->second.status == LandmarkStatus::kConfirmed &&
                        !it->second.moving;
      if (!kept) label = -1;
    }
  }
  return labels;
}

std::vector<Pose> FixedLagSmoother::WindowPoses() const {
  std::vector<Pose> out;
  for (const WindowPose& p : poses_) out.push_back(p.x);
  return out;
}

}  // namespace phdslam::reference
