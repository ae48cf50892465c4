// A Gaussian-mixture pose proposal with log-weights, its sampling rule and density
// (docs/algorithms/phd-slam.md section 4.1).
#pragma once

#include <optional>
#include <vector>

#include "src/core/types.h"

namespace phdslam::filters {

struct GaussianMixtureProposal {
  std::vector<double> log_weights;  ///< unnormalised log kappa_t
  std::vector<Pose> means;
  std::vector<Mat3> covs;

  [[nodiscard]] std::size_t size() const { return means.size(); }
  void Add(double log_weight, const Pose& mean, const Mat3& cov) {
    log_weights.push_back(log_weight);
    means.push_back(mean);
    covs.push_back(cov);
  }
  void Reserve(std::size_t n) {
    log_weights.reserve(n);
    means.reserve(n);
    covs.reserve(n);
  }
  void Clear() {
    log_weights.clear();
    means.clear();
    covs.clear();
  }
};

/// The mixture with its log-weights normalised and the lower Cholesky factors precomputed
/// (nullopt for a component whose covariance is not positive definite).
struct PreparedProposal {
  GaussianMixtureProposal mixture;        ///< log_weights normalised
  std::vector<std::optional<Mat3>> chol;  ///< lower Cholesky factors
  std::vector<double> log_norm;           ///< log of each component's Gaussian normaliser
  std::vector<Mat3> inv_chol;             ///< inverse lower factors, where chol exists
};

PreparedProposal PrepareProposal(GaussianMixtureProposal mixture);
/// The same, written into `out`, whose storage is reused (the filter prepares one proposal per
/// particle and step).
void PrepareProposal(GaussianMixtureProposal mixture, PreparedProposal& out);

/// The component picked by uniform u: the first t with cumulative normalised weight >= u, the
/// first component if rounding leaves none.
int PickComponent(const PreparedProposal& proposal, double u);

/// log q(x) = log sum_t kappa_t N(x; mu_t, Sigma_t), over components with a valid factor.
double LogMixtureDensity(const PreparedProposal& proposal, const Pose& x);

}  // namespace phdslam::filters
