// Moment matching of pose Gaussian mixtures: the Rao-Blackwellised pose covariance of a particle
// filter (the mixture over particles of each particle's own pose Gaussian before sampling).
//
// Headings are not wrapped in the suite (docs/algorithms/models.md section 1.2), but the components
// of one mixture may lie on different branches; every heading difference is therefore taken
// relative to a reference component and wrapped into [-pi, pi], and the matched mean keeps the
// reference's branch. The covariance is sum_t w_t (Sigma_t + d_t d_t^T), d_t = mu_t - mu (heading
// wrapped), symmetrised; it is positive semi-definite by construction (a sum of PSD terms with
// w_t >= 0).
#pragma once

#include <optional>
#include <span>

#include "src/core/types.h"
#include "src/filters/gaussian_mixture_proposal.h"

namespace phdslam::filters {

/// A weighted pose Gaussian: unnormalised log-weight, mean, covariance.
struct PoseMoments {
  double log_weight = 0.0;
  Pose mean = Pose::Zero();
  Mat3 cov = Mat3::Zero();
};

/// Mean and covariance of sum_t exp(w_t) N(mu_t, Sigma_t) / sum_t exp(w_t) over `components`
/// (log-weights need not be normalised; the first component is the heading reference). The
/// returned log_weight is log sum_t exp(w_t). nullopt when there are no components or every
/// weight is zero.
std::optional<PoseMoments> MatchMoments(std::span<const PoseMoments> components);

/// The moments of the distribution a prepared proposal samples from: its components with their
/// normalised weights, a component without a Cholesky factor counting as the point `fallback`
/// (the skeleton then keeps the predicted mean). The returned log_weight is 0.
PoseMoments ProposalMoments(const PreparedProposal& proposal, const Pose& fallback);

}  // namespace phdslam::filters
