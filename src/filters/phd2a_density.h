// PHD-SLAM 2.0a importance density (docs/algorithms/phd-slam.md section 4.7; Gao, Battistelli &
// Chisci, T-RO 2021): the predicted pose Gaussian is EKF-conditioned independently on every gated
// (component, measurement) pair, and the |M| x |Z| conditionals (plus the prior) are collapsed by
// moment matching into one Gaussian, which is sampled (the PHD-SLAM 3.0 authors sample; Gao's code
// takes the mean).
//
// The pair weights of Gao et al. (their eqs. 45-51) were not available. This class implements
// the following reconstruction, chosen so that the mixture being collapsed is the pose analogue
// of the GM-PHD posterior intensity of docs/algorithms/phd-slam.md section 3.2: one pose Gaussian
// per component of the updated map intensity, weighted like that component.
//
//  With (mu_0, Sigma_0) the predicted pose, and for each active component i with pD_i > 0
//  (point evaluation at mu_0, docs/algorithms/models.md section 3.3), Jacobians Hx, Hm at (mu_0,
//  m_i):
//    S_i    = Hx Sigma_0 Hx^T + Hm P_i Hm^T + R          (the cost-matrix S of
//    docs/algorithms/phd-slam.md section 4.3)
//    K_i    = Sigma_0 Hx^T S_i^-1
//  For each measurement z_j gated by i (nu_ij = z_j - h(m_i, mu_0), bearing wrapped,
//  nu_ij^T S_i^-1 nu_ij < T_G strictly):
//    EKF conditional   mu_ij = mu_0 + K_i nu_ij,  Sigma_i = Sigma_0 - K_i S_i K_i^T;
//    detection term    g_ij  = pD_i eta_i N(nu_ij; 0, S_i)              (eta_i = exp(log-weight));
//    pair weight       w_ij  = g_ij / (lambda_c + sum_i' g_i'j)         (per measurement, as in
//                                                                        the PHD update, with the
//                                                                        clutter intensity)
//  Prior term: N(mu_0, Sigma_0) with weight w_0 = sum_{i: pD_i > 0} (1 - pD_i) eta_i, the
//  misdetection mass of the updated intensity (a missed landmark says nothing about the pose).
//  The proposal is the single Gaussian moment-matched to {w_0: prior} u {w_ij: conditionals},
//  with log-weight 0; the importance weight is (45) with one component.
//
// Why these choices:
//  * S includes Hx Sigma_0 Hx^T because the pose is uncertain when the pairs are scored (the
//    description of 2.0a in docs/algorithms/phd-slam.md section 4.7 says so, and the same S gates
//    PHD-SLAM 3.0's cost matrix), and it is the innovation covariance of the very EKF that produces
//    mu_ij.
//  * Normalising per measurement with lambda_c in the denominator gives each measurement unit
//    mass shared between its landmark explanations and clutter; the clutter share is dropped (it
//    is not part of the posterior intensity), so a measurement that is probably clutter adds
//    almost nothing, and an unambiguous detection adds a conditional of weight about 1.
//  * Components with pD_i = 0 (outside the FOV but inside the buffered active set) are neither
//    detected nor missed; they carry no evidence and are left out of the prior term.
//  * Gating uses the same strict threshold T_G and the same S as the cost matrix.
// If no pair gates (or the map or the scan is empty) the proposal is the prior itself.
//
// best_association: for each measurement j, argmax_i g_ij when max_i g_ij > lambda_c (its best
// landmark explanation is more likely than clutter), else -1.
#pragma once

#include <span>

#include "src/filters/importance_density.h"

namespace phdslam::filters {

struct MomentMatchedGaussian {
  Pose mean = Pose::Zero();
  Mat3 cov = Mat3::Zero();
};

/// The Gaussian with the first two moments of the mixture sum_k exp(log_weights[k])
/// N(means[k], covs[k]) after normalising the weights: mean = sum w_k mu_k, cov = sum w_k
/// (Sigma_k + (mu_k - mean)(mu_k - mean)^T). Components of log-weight -inf are ignored.
/// Throws std::invalid_argument when the spans differ in size, are empty, or carry no finite
/// weight.
MomentMatchedGaussian MomentMatch(std::span<const double> log_weights, std::span<const Pose> means,
                                  std::span<const Mat3> covs);

class MergedEkfDensity final : public ImportanceDensity {
 public:
  /// Uses params.map.gate_threshold.
  explicit MergedEkfDensity(const PhdSlamParams& params) : params_(params) {}
  [[nodiscard]] ProposalOutput Build(const ProposalInput& input) const override;

 private:
  PhdSlamParams params_;
};

}  // namespace phdslam::filters
