#include "src/filters/phd2b_density.h"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "src/assignment/linear_assignment.h"
#include "src/core/angles.h"
#include "src/core/cholesky3.h"
#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/filters/gm_ipl_density.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {
namespace {

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

Eigen::MatrixXd JointIplResult::JointCovariance() const {
  const auto num_pairs = static_cast<Eigen::Index>(landmark_conditional_cov.size());
  Eigen::MatrixXd cov(3 + 2 * num_pairs, 3 + 2 * num_pairs);
  cov.topLeftCorner<3, 3>() = pose_covariance;
  for (Eigen::Index p = 0; p < num_pairs; ++p) {
    const Mat23& fp = landmark_pose_coupling[p];
    const Mat23 fp_sigma = fp * pose_covariance;
    cov.block<2, 3>(3 + 2 * p, 0) = fp_sigma;
    cov.block<3, 2>(0, 3 + 2 * p) = fp_sigma.transpose();
    for (Eigen::Index q = 0; q < num_pairs; ++q) {
      cov.block<2, 2>(3 + 2 * p, 3 + 2 * q) = fp_sigma * landmark_pose_coupling[q].transpose();
    }
    cov.block<2, 2>(3 + 2 * p, 3 + 2 * p) += landmark_conditional_cov[p];
  }
  return cov;
}

namespace {

/// One landmark's terms of an arrow-structured update at one linearisation.
struct PairTerms {
  Mat23 hx;
  Mat2 d_inv;      ///< D_p^-1
  Mat23 d_inv_hx;  ///< D_p^-1 Hx_p
  Vec2 d_inv_nu;   ///< D_p^-1 nu_p
  Mat2 p_hmt;      ///< P_p Hm_p^T
  Mat2 gain;       ///< G_p = P_p Hm_p^T D_p^-1
  Vec2 nu;
};

/// D_p^-1 for the symmetrised 2x2 D_p, or nothing when D_p is not positive definite.
std::optional<Mat2> InversePositiveDefinite2(const Mat2& d) {
  const Cholesky2 factor(d);
  if (!factor.positive_definite()) return std::nullopt;
  return factor.Inverse();
}

}  // namespace

JointIplResult JointIpl(const Pose& prior_mean, const Mat3& prior_cov,
                        std::span<const IplPair> pairs, const Mat2& noise_cov,
                        const JointIplOptions& options) {
  const auto num_pairs = static_cast<Eigen::Index>(pairs.size());
  const auto size = static_cast<std::size_t>(num_pairs);
  JointIplResult lin;
  lin.mean.resize(3 + 2 * num_pairs);
  lin.mean.head<3>() = prior_mean;
  lin.pose_covariance = prior_cov;
  lin.landmark_pose_coupling.assign(size, Mat23::Zero());
  lin.landmark_conditional_cov.resize(size);
  for (Eigen::Index p = 0; p < num_pairs; ++p) {
    lin.mean.segment<2>(3 + 2 * p) = pairs[p].landmark_mean;
    lin.landmark_conditional_cov[p] = pairs[p].landmark_cov;
  }
  if (num_pairs == 0) return lin;

  double nis_limit = std::numeric_limits<double>::infinity();
  if (options.nis_tail_probability > 0.0) {
    const int nz = static_cast<int>(2 * num_pairs);
    nis_limit = options.nis_quantiles != nullptr
                    ? (*options.nis_quantiles)(nz)
                    : ChiSquareUpperQuantileEvenDof(nz, options.nis_tail_probability);
  }
  std::vector<PairTerms> terms(size);
  Eigen::VectorXd next_mean(lin.mean.size());
  std::vector<Mat23> next_coupling(size);
  std::vector<Mat2> next_conditional(size);
  for (int l = 1; l <= options.max_iterations; ++l) {
    // Linearisation at the previous joint iterate: z_p ~ h(lin) + Hx_p (x - lin_x) +
    // Hm_p (m_p - lin_p) + r, restarted from the joint prior.
    const Pose lin_pose = lin.mean.head<3>();
    const Vec3 pose_offset = prior_mean - lin_pose;
    Mat3 w = Mat3::Zero();
    Vec3 b = Vec3::Zero();
    double nu_d_nu = 0.0;
    bool d_failed = false;
    for (Eigen::Index p = 0; p < num_pairs && !d_failed; ++p) {
      const Landmark lin_landmark = lin.mean.segment<2>(3 + 2 * p);
      const auto pj = models::PredictWithJacobians(lin_pose, lin_landmark);
      const IplPair& pair = pairs[p];
      PairTerms& t = terms[p];
      t.hx = pj.j.hx;
      // Innovation of the restart from the prior: z - (A x0 + b), b = h(lin) - A lin.
      t.nu =
          pair.z - pj.z_hat - pj.j.hx * pose_offset - pj.j.hm * (pair.landmark_mean - lin_landmark);
      t.nu(1) = WrapAngle(t.nu(1));
      t.p_hmt = pair.landmark_cov * pj.j.hm.transpose();
      Mat2 d = pj.j.hm * t.p_hmt + noise_cov;
      d = (0.5 * (d + d.transpose())).eval();
      const std::optional<Mat2> d_inv = InversePositiveDefinite2(d);
      if (!d_inv) {
        d_failed = true;
        break;
      }
      t.d_inv = *d_inv;
      t.d_inv_hx = t.d_inv * t.hx;
      t.d_inv_nu = t.d_inv * t.nu;
      t.gain = t.p_hmt * t.d_inv;
      w.noalias() += t.hx.transpose() * t.d_inv_hx;
      b.noalias() += t.hx.transpose() * t.d_inv_nu;
      nu_d_nu += t.nu.dot(t.d_inv_nu);
    }
    if (d_failed) {
      lin.cholesky_failed = true;
      break;
    }
    // Pose posterior: Sigma = Sigma_0 - Sigma_0 W (I + Sigma_0 W)^-1 Sigma_0, mean x0 + Sigma b.
    const Mat3 sigma0_w = prior_cov * w;
    Mat3 pose_cov = prior_cov - sigma0_w * (Mat3::Identity() + sigma0_w).inverse() * prior_cov;
    pose_cov = (0.5 * (pose_cov + pose_cov.transpose())).eval();
    const Vec3 pose_step = pose_cov * b;  // x_hat - x0 = Sigma b
    // nu^T S^-1 nu = sum nu_p^T D_p^-1 nu_p - b^T Sigma b.
    if (nu_d_nu - b.dot(pose_step) >= nis_limit) {
      lin.nis_stopped = true;
      break;
    }
    bool conditional_failed = !Cholesky3(pose_cov).positive_definite();
    next_mean.head<3>() = prior_mean + pose_step;
    for (Eigen::Index p = 0; p < num_pairs && !conditional_failed; ++p) {
      const PairTerms& t = terms[p];
      const IplPair& pair = pairs[p];
      // Given x: m_p = m_p0 + G_p (nu_p - Hx_p (x - x0)), Cov = P_p - G_p Hm_p P_p.
      next_mean.segment<2>(3 + 2 * p) = pair.landmark_mean + t.gain * (t.nu - t.hx * pose_step);
      next_coupling[p] = -t.gain * t.hx;
      Mat2 c = pair.landmark_cov - t.gain * t.p_hmt.transpose();
      c = (0.5 * (c + c.transpose())).eval();
      next_conditional[p] = c;
      conditional_failed = !Cholesky2(c).positive_definite();
    }
    if (conditional_failed) {
      lin.cholesky_failed = true;
      break;
    }
    const bool converged =
        l >= 2 && KlDivergence3(lin.mean.head<3>(), lin.pose_covariance, next_mean.head<3>(),
                                pose_cov) < options.kl_tolerance;
    lin.mean.swap(next_mean);
    lin.pose_covariance = pose_cov;
    lin.landmark_pose_coupling.swap(next_coupling);
    lin.landmark_conditional_cov.swap(next_conditional);
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
