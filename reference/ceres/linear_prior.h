// A Gaussian prior on some parameter blocks, kept as a whitened linear residual
//
//   r = A [x_1 - xbar_1; ...; x_n - xbar_n] + b,      cost 1/2 |r|^2,
//
// with xbar_i the block's linearisation point, fixed when the block entered the prior (first-
// estimate Jacobians: the prior's Jacobian A never changes, whatever the solver does with x).
// Headings are differences, never wrapped. It is what marginalisation leaves of the removed
// states (marginalization.h) and what a re-observed, marginalised landmark brings back into a
// window (fixed_lag_smoother.h).
#pragma once

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <vector>

namespace phdslam::reference {

struct LinearPrior {
  std::vector<double*> blocks;                        ///< the parameter blocks it constrains
  std::vector<Eigen::VectorXd> linearization_points;  ///< xbar_i, one per block
  Eigen::MatrixXd a;                                  ///< rows x sum of the block sizes
  Eigen::VectorXd b;                                  ///< rows

  [[nodiscard]] int Dimension() const { return static_cast<int>(a.cols()); }
  [[nodiscard]] bool Empty() const { return a.rows() == 0; }
  /// Index of `block` in `blocks`, or -1.
  [[nodiscard]] int IndexOf(const double* block) const;
};

/// The prior N(mean, cov) on one block: A = L^-1 with cov = L L^T, b = 0, xbar = mean. Throws
/// std::invalid_argument when cov is not positive definite.
LinearPrior GaussianPrior(double* block, const Eigen::VectorXd& mean, const Eigen::MatrixXd& cov);

/// The prior as a Ceres residual on its blocks (analytic: the Jacobian of block i is the
/// columns of A that belong to it). Keeps a copy of the prior.
class LinearPriorFactor final : public ceres::CostFunction {
 public:
  explicit LinearPriorFactor(LinearPrior prior);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  static ceres::CostFunction* Create(const LinearPrior& prior) {
    return new LinearPriorFactor(prior);
  }

 private:
  LinearPrior prior_;
  std::vector<int> offsets_;
};

}  // namespace phdslam::reference
