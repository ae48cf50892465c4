// The factor graph of one smoother solve: odometry factors along the pose chain and a
// range-bearing factor per associated measurement (README.md, "The graph"). Shared by the batch
// solve and the incremental one, which holds the older poses constant while it optimises the
// newest part of a growing graph.
#pragma once

#include <ceres/ceres.h>

#include <memory>
#include <optional>
#include <vector>

#include "datasets/scenario.h"
#include "reference/ceres/landmark_association.h"
#include "reference/ceres/odometry_increment.h"
#include "src/core/types.h"

namespace phdslam::reference {

enum class SparseLinearSolver {
  kSparseNormalCholesky,  ///< default: CHOLMOD on J^T J with a fill-reducing ordering
  kSparseSchur,           ///< landmarks eliminated first, then a sparse Cholesky on the poses
};

/// How the odometry of a solve is modelled.
struct OdometrySpec {
  const std::vector<OdometryIncrement>* increments;  ///< pose-space increments with the floor
  OdometryNoiseFloor floor;
  bool control_space;  ///< VelocityOdometryFactor where it applies
};

/// Solver settings of one Optimise call.
struct SolveSettings {
  int max_iterations = 100;
  double function_tolerance = 1e-9;
  int num_threads = 1;
  SparseLinearSolver linear_solver = SparseLinearSolver::kSparseNormalCholesky;
};

/// The odometry factor of step k (linking pose k-1, or the anchor, to pose k).
ceres::CostFunction* MakeOdometryCost(const datasets::Scenario& scenario, std::size_t k,
                                      const OdometrySpec& spec);

class HeldMeasurementPriors;

/// The factor graph of the first association.size() steps. Parameter blocks point into `poses`
/// and `landmarks`, which must not be resized while the graph lives. Only landmarks referenced by
/// the association enter the problem. Poses before `held_before` are held constant (the
/// incremental solve); the odometry factors between two held poses are left out. With
/// `held_priors` (which must have folded the steps before held_before), the measurements taken
/// from held poses are replaced by each landmark's folded prior (held_measurement_prior.h).
class FactorGraph {
 public:
  FactorGraph(const datasets::Scenario& scenario, const OdometrySpec& odometry,
              const Association& association, ceres::LossFunction* loss, std::vector<Pose>* poses,
              std::vector<Landmark>* landmarks, std::size_t held_before = 0,
              const HeldMeasurementPriors* held_priors = nullptr);

  ceres::Solver::Summary Optimise(const SolveSettings& settings);

  /// Marginal covariances of every pose and landmark block (held poses and pose 0 when it is the
  /// known initial pose: zero). False when ceres::Covariance fails or a landmark is not in the
  /// graph.
  bool Covariances(int num_threads, std::vector<std::optional<Mat3>>* pose_covs,
                   std::vector<Mat2>* landmark_covs);

  /// Marginal covariance of the newest pose and of the landmarks `indices` in this graph (which
  /// is conditional on the held poses); with `pose_cross`, also each landmark's
  /// cross-covariance with the newest pose, Cov(m, x) (zero when that pose is held). False when
  /// ceres::Covariance fails.
  bool NewestCovariances(const std::vector<int>& indices, Mat3* pose_cov,
                         std::vector<Mat2>* landmark_covs,
                         std::vector<Eigen::Matrix<double, 2, 3>>* pose_cross = nullptr);

  /// Range-bearing residual blocks (associated measurements in the problem).
  [[nodiscard]] std::size_t residuals() const { return residuals_; }
  /// Landmark prior blocks (measurements of held poses folded).
  [[nodiscard]] std::size_t priors() const { return priors_; }
  [[nodiscard]] bool HasLandmark(std::size_t i) const {
    return problem_->HasParameterBlock((*landmarks_)[i].data());
  }

 private:
  [[nodiscard]] bool PoseVariable(std::size_t k) const;

  Pose anchor_;
  std::size_t steps_;
  std::size_t held_before_;
  std::vector<Pose>* poses_;
  std::vector<Landmark>* landmarks_;
  std::unique_ptr<ceres::Problem> problem_;
  bool pose0_constant_ = false;
  std::size_t residuals_ = 0;
  std::size_t priors_ = 0;
};

}  // namespace phdslam::reference
