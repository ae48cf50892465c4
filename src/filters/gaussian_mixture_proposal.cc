#include "src/filters/gaussian_mixture_proposal.h"

#include <Eigen/LU>
#include <cmath>
#include <numbers>

#include "src/core/cholesky3.h"
#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"

namespace phdslam::filters {

void PrepareProposal(GaussianMixtureProposal mixture, PreparedProposal& out) {
  const double total = LogSumExp(mixture.log_weights);
  for (double& w : mixture.log_weights) w -= total;
  const std::size_t n = mixture.size();
  out.chol.assign(n, std::nullopt);
  out.log_norm.assign(n, kNegInf);
  out.inv_chol.assign(n, Mat3::Zero());
  for (std::size_t t = 0; t < n; ++t) {
    // Cholesky3 gives CholeskyLower<3>, the triangular solve of the identity and the log
    // diagonal sum bit for bit.
    const Cholesky3 factor(mixture.covs[t]);
    if (factor.positive_definite()) {
      out.chol[t] = factor.L();
      out.inv_chol[t] = factor.InverseOfL();
      out.log_norm[t] = -1.5 * std::log(2.0 * std::numbers::pi) - factor.LogDiagonalSum();
    }
  }
  out.mixture = std::move(mixture);
}

PreparedProposal PrepareProposal(GaussianMixtureProposal mixture) {
  PreparedProposal p;
  PrepareProposal(std::move(mixture), p);
  return p;
}

int PickComponent(const PreparedProposal& proposal, double u) {
  double cumulative = 0.0;
  const auto& w = proposal.mixture.log_weights;
  for (std::size_t t = 0; t < w.size(); ++t) {
    cumulative += std::exp(w[t]);
    if (cumulative >= u) return static_cast<int>(t);
  }
  return 0;
}

double LogMixtureDensity(const PreparedProposal& proposal, const Pose& x) {
  double acc = kNegInf;
  for (std::size_t t = 0; t < proposal.mixture.size(); ++t) {
    if (!proposal.chol[t]) continue;
    const Vec3 w = proposal.inv_chol[t] * (x - proposal.mixture.means[t]);
    acc = LogAddExp(acc,
                    proposal.mixture.log_weights[t] + proposal.log_norm[t] - 0.5 * w.squaredNorm());
  }
  return acc;
}

}  // namespace phdslam::filters
