#include "validation/metrics/nees.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>
#include <string>

namespace phdslam::validation {
namespace {

template <int N>
double Nees(const Eigen::Matrix<double, N, 1>& error, const Eigen::Matrix<double, N, N>& cov,
            const char* caller) {
  if (!error.allFinite() || !cov.allFinite()) {
    throw std::invalid_argument(std::string(caller) + ": error or covariance is not finite");
  }
  const double scale = cov.cwiseAbs().maxCoeff();
  if (!((cov - cov.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * scale)) {
    throw std::invalid_argument(std::string(caller) + ": covariance is not symmetric");
  }
  const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(cov);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument(std::string(caller) +
                                ": covariance is not positive definite (no NEES for it)");
  }
  const Eigen::Matrix<double, N, 1> whitened = llt.matrixL().solve(error);
  return whitened.squaredNorm();
}

}  // namespace

double PoseNees(const Pose& truth, const Pose& estimate, const Mat3& cov) {
  return Nees<3>(truth - estimate, cov, "PoseNees");
}

double LandmarkNees(const Landmark& truth, const Landmark& estimate, const Mat2& cov) {
  return Nees<2>(truth - estimate, cov, "LandmarkNees");
}

double EllipsoidThreshold(int dim, double level) {
  if (dim < 1 || !(level > 0.0 && level < 1.0)) {
    throw std::invalid_argument("EllipsoidThreshold: dim = " + std::to_string(dim) + ", level = " +
                                std::to_string(level) + "; expected dim >= 1 and 0 < level < 1");
  }
  return ChiSquareQuantile(level, static_cast<double>(dim));
}

NeesBounds AveragedNeesBounds(int dim, int runs, double alpha) {
  if (dim < 1 || runs < 1) {
    throw std::invalid_argument("AveragedNeesBounds: dim = " + std::to_string(dim) +
                                ", runs = " + std::to_string(runs) + "; expected both >= 1");
  }
  if (!(alpha > 0.0 && alpha < 1.0)) {
    throw std::invalid_argument("AveragedNeesBounds: alpha = " + std::to_string(alpha) +
                                "; expected 0 < alpha < 1");
  }
  const double dof = static_cast<double>(dim) * runs;
  return {ChiSquareQuantile(0.5 * alpha, dof) / runs,
          ChiSquareQuantile(1.0 - 0.5 * alpha, dof) / runs};
}

NeesConsistency SummariseNees(const std::vector<std::vector<double>>& nees_per_run_per_step,
                              int dim, double alpha) {
  if (nees_per_run_per_step.empty()) {
    throw std::invalid_argument("SummariseNees: no runs");
  }
  const std::size_t steps = nees_per_run_per_step.front().size();
  if (steps == 0) throw std::invalid_argument("SummariseNees: run 0 has no steps");
  for (std::size_t r = 0; r < nees_per_run_per_step.size(); ++r) {
    if (nees_per_run_per_step[r].size() != steps) {
      throw std::invalid_argument("SummariseNees: run " + std::to_string(r) + " has " +
                                  std::to_string(nees_per_run_per_step[r].size()) +
                                  " steps; expected " + std::to_string(steps) + " like run 0");
    }
  }
  const int runs = static_cast<int>(nees_per_run_per_step.size());
  NeesConsistency result;
  result.bounds = AveragedNeesBounds(dim, runs, alpha);
  result.mean_nees.assign(steps, 0.0);
  for (const auto& run : nees_per_run_per_step) {
    for (std::size_t k = 0; k < steps; ++k) result.mean_nees[k] += run[k];
  }
  std::size_t inside = 0;
  for (double& mean : result.mean_nees) {
    mean /= runs;
    if (mean >= result.bounds.lower && mean <= result.bounds.upper) ++inside;
  }
  result.fraction_inside = static_cast<double>(inside) / static_cast<double>(steps);
  return result;
}

std::vector<double> MatchedLandmarkNees(const std::vector<Landmark>& truth,
                                        const std::vector<Landmark>& estimate,
                                        const std::vector<Mat2>& estimate_covs,
                                        const GospaResult& gospa) {
  if (estimate_covs.size() != estimate.size()) {
    throw std::invalid_argument("MatchedLandmarkNees: " + std::to_string(estimate.size()) +
                                " estimates but " + std::to_string(estimate_covs.size()) +
                                " covariances; expected one each");
  }
  std::vector<double> nees;
  nees.reserve(gospa.pairs.size());
  for (const auto& [t, e] : gospa.pairs) {
    if (t < 0 || t >= static_cast<int>(truth.size()) || e < 0 ||
        e >= static_cast<int>(estimate.size())) {
      throw std::invalid_argument("MatchedLandmarkNees: pair (" + std::to_string(t) + ", " +
                                  std::to_string(e) + ") is out of range for " +
                                  std::to_string(truth.size()) + " true and " +
                                  std::to_string(estimate.size()) + " estimated landmarks");
    }
    nees.push_back(LandmarkNees(truth[t], estimate[e], estimate_covs[e]));
  }
  return nees;
}

}  // namespace phdslam::validation
