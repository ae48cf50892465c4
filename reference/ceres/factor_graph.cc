#include "reference/ceres/factor_graph.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "reference/ceres/held_measurement_prior.h"
#include "reference/ceres/odometry_factor.h"
#include "reference/ceres/ordered_covariance.h"
#include "reference/ceres/range_bearing_factor.h"
#include "reference/ceres/velocity_odometry_factor.h"
#include "src/core/gaussian.h"

namespace phdslam::reference {
namespace {

ceres::SparseLinearAlgebraLibraryType SparseLibrary() {
  return ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)
             ? ceres::SUITE_SPARSE
             : ceres::EIGEN_SPARSE;
}

using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
using RowMajor2 = Eigen::Matrix<double, 2, 2, Eigen::RowMajor>;

}  // namespace

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

FactorGraph::FactorGraph(const datasets::Scenario& scenario, const OdometrySpec& odometry,
                         const Association& association, ceres::LossFunction* loss,
                         std::vector<Pose>* poses, std::vector<Landmark>* landmarks,
                         std::size_t held_before, const HeldMeasurementPriors* held_priors)
    : anchor_(scenario.initial_pose),
      steps_(association.size()),
      held_before_(held_before),
      poses_(poses),
      landmarks_(landmarks) {
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_ = std::make_unique<ceres::Problem>(problem_options);
  if (steps_ == 0) return;
  for (std::size_t k = held_before_; k < steps_; ++k) {
    problem_->AddParameterBlock((*poses)[k].data(), 3);
  }

  // Gauge: the initial pose is known exactly. Without propagation at step 0, pose 0 is that pose
  // and is held constant; otherwise a constant anchor block holds it and step 0's odometry links
  // the anchor to pose 0.
  if ((*odometry.increments)[0].propagated) {
    if (held_before_ == 0) {
      problem_->AddParameterBlock(anchor_.data(), 3);
      problem_->SetParameterBlockConstant(anchor_.data());
      problem_->AddResidualBlock(MakeOdometryCost(scenario, 0, odometry), nullptr, anchor_.data(),
                                 (*poses)[0].data());
    }
  } else {
    (*poses)[0] = scenario.initial_pose;
    if (held_before_ == 0) {
      problem_->SetParameterBlockConstant((*poses)[0].data());
      pose0_constant_ = true;
    }
  }
  for (std::size_t k = std::max<std::size_t>(held_before_, 1); k < steps_; ++k) {
    problem_->AddResidualBlock(MakeOdometryCost(scenario, k, odometry), nullptr,
                               (*poses)[k - 1].data(), (*poses)[k].data());
  }
  // With held poses, a landmark seen only from held poses is held too: left out of the graph.
  std::vector<bool> active(landmarks->size(), held_before_ == 0);
  for (std::size_t k = held_before_; k < association.size(); ++k) {
    for (int i : association[k]) {
      if (i != kUnassociated) active[static_cast<std::size_t>(i)] = true;
    }
  }
  const Mat2 w = WhiteningMatrix<2>(scenario.sensor.noise_cov);
  if (held_priors != nullptr && held_priors->folded() < std::min(held_before_, steps_)) {
    throw std::invalid_argument("FactorGraph: the held measurement priors miss held steps");
  }
  const std::size_t first_measured = held_priors != nullptr ? held_before_ : 0;
  for (std::size_t k = first_measured; k < association.size(); ++k) {
    for (std::size_t j = 0; j < association[k].size(); ++j) {
      const int i = association[k][j];
      if (i == kUnassociated || !active[static_cast<std::size_t>(i)]) continue;
      problem_->AddResidualBlock(
          RangeBearingFactor::Create(scenario.steps[k].data.measurements[j], w), loss,
          (*poses)[k].data(), (*landmarks)[static_cast<std::size_t>(i)].data());
      ++residuals_;
    }
  }
  if (held_priors != nullptr) {
    for (std::size_t i = 0; i < landmarks->size(); ++i) {
      if (!active[i] || !held_priors->Has(i)) continue;
      ceres::CostFunction* prior = held_priors->MakeFactor(i, (*landmarks)[i].data());
      if (prior == nullptr) continue;
      problem_->AddResidualBlock(prior, nullptr, (*landmarks)[i].data());
      ++priors_;
    }
  }
  for (std::size_t k = 0; k < std::min(held_before_, steps_); ++k) {
    if (problem_->HasParameterBlock((*poses)[k].data())) {
      problem_->SetParameterBlockConstant((*poses)[k].data());
    }
  }
}

bool FactorGraph::PoseVariable(std::size_t k) const {
  if (k == 0 && pose0_constant_) return false;
  return k >= held_before_;
}

ceres::Solver::Summary FactorGraph::Optimise(const SolveSettings& settings) {
  ceres::Solver::Options o;
  // Sparse normal Cholesky (CHOLMOD, AMD ordering) by default: the graph is a long pose chain with
  // ~160 landmarks each seen from hundreds of poses. Eliminating the chain leaves a small dense
  // landmark front, while the Schur complement on the poses couples every pair of poses that see
  // a common landmark (a band several hundred poses wide). README.md has timings.
  o.linear_solver_type = settings.linear_solver == SparseLinearSolver::kSparseSchur
                             ? ceres::SPARSE_SCHUR
                             : ceres::SPARSE_NORMAL_CHOLESKY;
  o.sparse_linear_algebra_library_type = SparseLibrary();
  if (settings.linear_solver == SparseLinearSolver::kSparseSchur) {
    auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
    for (Landmark& m : *landmarks_) {
      if (problem_->HasParameterBlock(m.data())) ordering->AddElementToGroup(m.data(), 0);
    }
    for (std::size_t k = 0; k < steps_; ++k) {
      if (problem_->HasParameterBlock((*poses_)[k].data())) {
        ordering->AddElementToGroup((*poses_)[k].data(), 1);
      }
    }
    if (problem_->HasParameterBlock(anchor_.data())) ordering->AddElementToGroup(anchor_.data(), 1);
    o.linear_solver_ordering = ordering;
  }
  o.max_num_iterations = settings.max_iterations;
  o.function_tolerance = settings.function_tolerance;
  o.num_threads = settings.num_threads;
  o.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(o, problem_.get(), &summary);
  return summary;
}

bool FactorGraph::Covariances(int num_threads, std::vector<std::optional<Mat3>>* pose_covs,
                              std::vector<Mat2>* landmark_covs) {
  // SPARSE_QR (SuiteSparseQR when available) factors the Jacobian once and back-substitutes per
  // column; DENSE_SVD would need the dense 12,000 x 12,000 information matrix of the paper
  // scenario.
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::SPARSE_QR;
  co.sparse_linear_algebra_library_type = SparseLibrary();
  co.num_threads = num_threads;
  OrderedCovariance covariance(co);
  std::vector<std::pair<const double*, const double*>> blocks;
  for (std::size_t k = 0; k < steps_; ++k) {
    if (PoseVariable(k)) blocks.emplace_back((*poses_)[k].data(), (*poses_)[k].data());
  }
  for (const Landmark& m : *landmarks_) {
    if (!problem_->HasParameterBlock(m.data())) return false;
    blocks.emplace_back(m.data(), m.data());
  }
  if (!covariance.Compute(blocks, problem_.get())) return false;
  pose_covs->assign(steps_, std::nullopt);
  for (std::size_t k = 0; k < steps_; ++k) {
    if (!PoseVariable(k)) {
      (*pose_covs)[k] = Mat3::Zero();
      continue;
    }
    RowMajor3 c;
    if (!covariance.GetCovarianceBlock((*poses_)[k].data(), (*poses_)[k].data(), c.data())) {
      return false;
    }
    Mat3 p = c;
    Symmetrize(p);
    (*pose_covs)[k] = p;
  }
  landmark_covs->clear();
  for (const Landmark& m : *landmarks_) {
    RowMajor2 c;
    if (!covariance.GetCovarianceBlock(m.data(), m.data(), c.data())) return false;
    Mat2 p = c;
    Symmetrize(p);
    landmark_covs->push_back(p);
  }
  return true;
}

bool FactorGraph::NewestCovariances(const std::vector<int>& indices, Mat3* pose_cov,
                                    std::vector<Mat2>* landmark_covs,
                                    std::vector<Eigen::Matrix<double, 2, 3>>* pose_cross) {
  if (steps_ == 0) return false;
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::SPARSE_QR;
  co.sparse_linear_algebra_library_type = SparseLibrary();
  OrderedCovariance covariance(co);
  const double* newest = (*poses_)[steps_ - 1].data();
  const bool pose_variable = PoseVariable(steps_ - 1);
  std::vector<std::pair<const double*, const double*>> blocks;
  if (pose_variable) blocks.emplace_back(newest, newest);
  for (int i : indices) {
    const double* m = (*landmarks_)[static_cast<std::size_t>(i)].data();
    if (!problem_->HasParameterBlock(m)) return false;
    blocks.emplace_back(m, m);
    if (pose_cross != nullptr && pose_variable) blocks.emplace_back(m, newest);
  }
  if (!covariance.Compute(blocks, problem_.get())) return false;
  *pose_cov = Mat3::Zero();
  if (pose_variable) {
    RowMajor3 c;
    if (!covariance.GetCovarianceBlock(newest, newest, c.data())) return false;
    *pose_cov = c;
    Symmetrize(*pose_cov);
  }
  landmark_covs->clear();
  for (int i : indices) {
    const double* m = (*landmarks_)[static_cast<std::size_t>(i)].data();
    RowMajor2 c;
    if (!covariance.GetCovarianceBlock(m, m, c.data())) return false;
    Mat2 p = c;
    Symmetrize(p);
    landmark_covs->push_back(p);
  }
  if (pose_cross == nullptr) return true;
  pose_cross->assign(indices.size(), Eigen::Matrix<double, 2, 3>::Zero());
  if (!pose_variable) return true;
  for (std::size_t n = 0; n < indices.size(); ++n) {
    const double* m = (*landmarks_)[static_cast<std::size_t>(indices[n])].data();
    Eigen::Matrix<double, 2, 3, Eigen::RowMajor> c;
    if (!covariance.GetCovarianceBlock(m, newest, c.data())) return false;
    (*pose_cross)[n] = c;
  }
  return true;
}

}  // namespace phdslam::reference
