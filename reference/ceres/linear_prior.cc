#include "reference/ceres/linear_prior.h"

#include <Eigen/Cholesky>
#include <stdexcept>
#include <utility>

namespace phdslam::reference {

int LinearPrior::IndexOf(const double* block) const {
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (blocks[i] == block) return static_cast<int>(i);
  }
  return -1;
}

LinearPrior GaussianPrior(double* block, const Eigen::VectorXd& mean, const Eigen::MatrixXd& cov) {
  const Eigen::LLT<Eigen::MatrixXd> llt(cov);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("GaussianPrior: covariance is not positive definite");
  }
  LinearPrior p;
  p.blocks = {block};
  p.linearization_points = {mean};
  const Eigen::MatrixXd l = llt.matrixL();
  p.a = l.triangularView<Eigen::Lower>().solve(Eigen::MatrixXd::Identity(mean.size(), mean.size()));
  p.b = Eigen::VectorXd::Zero(mean.size());
  return p;
}

LinearPriorFactor::LinearPriorFactor(LinearPrior prior) : prior_(std::move(prior)) {
  int offset = 0;
  for (const Eigen::VectorXd& xbar : prior_.linearization_points) {
    offsets_.push_back(offset);
    mutable_parameter_block_sizes()->push_back(static_cast<int>(xbar.size()));
    offset += static_cast<int>(xbar.size());
  }
  set_num_residuals(static_cast<int>(prior_.a.rows()));
}

bool LinearPriorFactor::Evaluate(double const* const* parameters, double* residuals,
                                 double** jacobians) const {
  Eigen::VectorXd dx(prior_.a.cols());
  for (std::size_t i = 0; i < prior_.blocks.size(); ++i) {
    const auto n = prior_.linearization_points[i].size();
    dx.segment(offsets_[i], n) =
        Eigen::Map<const Eigen::VectorXd>(parameters[i], n) - prior_.linearization_points[i];
  }
  Eigen::Map<Eigen::VectorXd>(residuals, prior_.a.rows()) = prior_.a * dx + prior_.b;
  if (jacobians == nullptr) return true;
  for (std::size_t i = 0; i < prior_.blocks.size(); ++i) {
    if (jacobians[i] == nullptr) continue;
    const auto n = prior_.linearization_points[i].size();
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        jacobians[i], prior_.a.rows(), n) = prior_.a.middleCols(offsets_[i], n);
  }
  return true;
}

}  // namespace phdslam::reference
