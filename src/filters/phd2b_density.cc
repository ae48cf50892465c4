#include "src/filters/phd2b_density.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "src/assignment/linear_assignment.h"
#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/filters/gm_ipl_density.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {
namespace {

ProposalOutput PriorProposal(const ProposalInput& input) {
  ProposalOutput out;
  out.mixture.Add(0.0, input.predicted_mean, input.predicted_cov);
  out.best_association.assign(input.measurements.size(), -1);
  return out;
}

/// True when the symmetric matrix p is numerically positive definite (every pivot > 0, finite).
bool IsPositiveDefinite(const Eigen::MatrixXd& p) {
  return LltIsPositiveDefinite(Eigen::LLT<Eigen::MatrixXd>(p));
}

/// log of the chi-square survival function for even dof = 2k:
/// Q(x) = exp(-x/2) sum_{i<k} (x/2)^i / i!.
double LogChiSquareSurvivalEvenDof(int k, double x) {
  const double h = 0.5 * x;
  double acc = kNegInf;
  double log_term = 0.0;  // log(h^i / i!)
  for (int i = 0; i < k; ++i) {
    if (i > 0) log_term += std::log(h) - std::log(static_cast<double>(i));
    acc = LogAddExp(acc, log_term);
  }
  return acc - h;
}

}  // namespace

double ChiSquareUpperQuantileEvenDof(int dof, double tail_probability) {
  if (dof < 2 || dof % 2 != 0) {
    throw std::invalid_argument("ChiSquareUpperQuantileEvenDof: dof must be even and >= 2, got " +
                                std::to_string(dof));
  }
  if (!(tail_probability > 0.0 && tail_probability < 1.0)) {
    throw std::invalid_argument(
        "ChiSquareUpperQuantileEvenDof: tail_probability must lie in (0, 1)");
  }
  const int k = dof / 2;
  const double log_tail = std::log(tail_probability);
  // Q is decreasing in x: bracket, then bisect.
  double lo = 0.0;
  double hi = static_cast<double>(dof) + 10.0;
  while (LogChiSquareSurvivalEvenDof(k, hi) > log_tail) hi *= 2.0;
  for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (LogChiSquareSurvivalEvenDof(k, mid) > log_tail) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

EvenDofChiSquareQuantiles::EvenDofChiSquareQuantiles(double tail_probability)
    : tail_probability_(tail_probability) {
  if (!(tail_probability > 0.0 && tail_probability < 1.0)) {
    throw std::invalid_argument("EvenDofChiSquareQuantiles: tail_probability must lie in (0, 1)");
  }
}

double EvenDofChiSquareQuantiles::operator()(int dof) {
  if (dof < 2 || dof % 2 != 0) return ChiSquareUpperQuantileEvenDof(dof, tail_probability_);
  const auto half = static_cast<std::size_t>(dof / 2);
  if (by_half_dof_.size() <= half) {
    by_half_dof_.resize(half + 1, std::numeric_limits<double>::quiet_NaN());
  }
  if (std::isnan(by_half_dof_[half])) {
    by_half_dof_[half] = ChiSquareUpperQuantileEvenDof(dof, tail_probability_);
  }
  return by_half_dof_[half];
}

JointIplResult JointIpl(const Pose& prior_mean, const Mat3& prior_cov,
                        std::span<const IplPair> pairs, const Mat2& noise_cov,
                        const JointIplOptions& options) {
  const int num_pairs = static_cast<int>(pairs.size());
  const int n = 3 + 2 * num_pairs;
  const int nz = 2 * num_pairs;

  Eigen::VectorXd x0(n);
  Eigen::MatrixXd p0 = Eigen::MatrixXd::Zero(n, n);
  x0.head<3>() = prior_mean;
  p0.topLeftCorner<3, 3>() = prior_cov;
  for (int p = 0; p < num_pairs; ++p) {
    x0.segment<2>(3 + 2 * p) = pairs[p].landmark_mean;
    p0.block<2, 2>(3 + 2 * p, 3 + 2 * p) = pairs[p].landmark_cov;
  }
  JointIplResult lin{x0, p0, 0, false};
  if (num_pairs == 0) return lin;

  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(nz, n);
  Eigen::VectorXd nu(nz);
  Eigen::MatrixXd s(nz, nz);
  double nis_limit = std::numeric_limits<double>::infinity();
  if (options.nis_tail_probability > 0.0) {
    nis_limit = options.nis_quantiles != nullptr
                    ? (*options.nis_quantiles)(nz)
                    : ChiSquareUpperQuantileEvenDof(nz, options.nis_tail_probability);
  }
  for (int l = 1; l <= options.max_iterations; ++l) {
    // Stacked linearisation at the previous joint iterate: z ~ h(lin) + H (x - lin) + r.
    const Pose lin_pose = lin.mean.head<3>();
    const Vec3 pose_offset = prior_mean - lin_pose;
    for (Eigen::Index p = 0; p < num_pairs; ++p) {
      const Landmark lin_landmark = lin.mean.segment<2>(3 + 2 * p);
      const auto j = models::MeasurementJacobians(lin_pose, lin_landmark);
      h.block<2, 3>(2 * p, 0) = j.hx;
      h.block<2, 2>(2 * p, 3 + 2 * p) = j.hm;
      // Innovation of the restart from the prior: z - (A x0 + b), b = h(lin) - A lin.
      Vec2 r = pairs[p].z - models::PredictMeasurement(lin_pose, lin_landmark) -
               j.hx * pose_offset - j.hm * (pairs[p].landmark_mean - lin_landmark);
      r(1) = WrapAngle(r(1));
      nu.segment<2>(2 * p) = r;
    }
    // One stacked Kalman update of the dense joint prior.
    const Eigen::MatrixXd pht = p0 * h.transpose();
    s.noalias() = h * pht;
    for (Eigen::Index p = 0; p < num_pairs; ++p) s.block<2, 2>(2 * p, 2 * p) += noise_cov;
    s = (0.5 * (s + s.transpose())).eval();
    const Eigen::LLT<Eigen::MatrixXd> s_llt(s);
    if (s_llt.info() != Eigen::Success) {
      lin.cholesky_failed = true;
      break;
    }
    if (nu.dot(s_llt.solve(nu)) >= nis_limit) {
      lin.nis_stopped = true;
      break;
    }
    const Eigen::MatrixXd gain = s_llt.solve(pht.transpose()).transpose();  // P H^T S^-1
    Eigen::VectorXd m = x0 + gain * nu;
    Eigen::MatrixXd cov = p0;
    cov.noalias() -= gain * pht.transpose();
    cov = (0.5 * (cov + cov.transpose())).eval();
    if (!IsPositiveDefinite(cov)) {
      lin.cholesky_failed = true;
      break;
    }
    const bool converged =
        l >= 2 && KlDivergence3(lin.mean.head<3>(), lin.cov.topLeftCorner<3, 3>(), m.head<3>(),
                                cov.topLeftCorner<3, 3>()) < options.kl_tolerance;
    lin.mean = std::move(m);
    lin.cov = std::move(cov);
    lin.iterations = l;
    if (converged) break;
  }
  return lin;
}

ProposalOutput JointIplDensity::Build(const ProposalInput& input) const {
  const std::span<const phd::GaussianComponent> active = input.landmarks;
  if (active.empty() || input.measurements.empty()) return PriorProposal(input);
  const AssociationCosts costs = BuildAssociationCosts(input, params_);
  if (costs.rows.empty()) return PriorProposal(input);

  const std::optional<assignment::Assignment> best = assignment::SolveLinearAssignment(costs.cost);
  if (!best) {
    // Every misdetection entry is finite, so a feasible assignment always exists.
    throw std::runtime_error(
        "JointIplDensity: the association cost matrix has no feasible "
        "assignment (expected finite misdetection entries)");
  }
  const int k = static_cast<int>(costs.cols.size());
  ProposalOutput out;
  out.best_association.assign(input.measurements.size(), -1);
  std::vector<IplPair> pairs;
  // Rows are in ascending active-list order, so the landmarks enter the state in that order.
  for (std::size_t a = 0; a < costs.rows.size(); ++a) {
    const int col = best->row_to_col[a];
    if (col >= k) continue;
    const int component = costs.rows[a];
    const int measurement = costs.cols[col];
    pairs.push_back(
        {active[component].mean, active[component].cov, input.measurements[measurement]});
    out.best_association[measurement] = component;
  }
  if (pairs.empty()) {
    out.mixture.Add(0.0, input.predicted_mean, input.predicted_cov);
    return out;
  }
  const JointIplResult joint =
      JointIpl(input.predicted_mean, input.predicted_cov, pairs, input.sensor->noise_cov,
               {params_.ipl_iterations, params_.ipl_kl_tolerance, nis_tail_probability_,
                nis_quantiles_ ? &*nis_quantiles_ : nullptr});
  out.mixture.Add(0.0, joint.pose_mean(), joint.pose_cov());
  return out;
}

}  // namespace phdslam::filters
