// PHD-SLAM 2.0b importance density (docs/algorithms/phd-slam.md section 4.8; Kaltiokallio et al.,
// SPAWC 2022, as the PHD-SLAM 3.0 paper describes it): a joint iterated posterior linearisation
// (IPL) of the pose and the associated landmarks for the single best data association, whose pose
// marginal is the proposal.
//
// Build():
//  1. The gated cost matrix of docs/algorithms/phd-slam.md section 4.3 (BuildAssociationCosts,
//     shared with PHD-SLAM 3.0) is solved for its single best assignment (exact linear assignment:
//     the first hypothesis of Murty's ranking). best_association is read from it.
//  2. The detected components i_1 < ... < i_M (active-list order) form the augmented state
//     [x; m_i1; ...; m_iM] with prior N([mu_0; m_i1; ...], blkdiag(Sigma_0, P_i1, ...)).
//  3. JointIpl runs the IPL of docs/algorithms/phd-slam.md section 4.5 on this state: every
//     iteration restarts from the joint prior and applies one stacked Kalman update of all M
//     measurements, linearised (Jacobians w.r.t. pose and landmarks) at the previous joint iterate
//     (the prior in iteration 1). The statistical linear regression is first order, so A = [Hx, Hm]
//     and Omega = R.
//  4. The proposal is the pose marginal of the result, a single Gaussian with log-weight 0, so
//     the importance weight is (45) with one component, log N(x; mu_0, Sigma_0) - log q(x).
//
// Arrow structure: the prior is blkdiag(Sigma_0, P_1, ..., P_M) and measurement p depends on the
// pose and landmark p only, so the posterior information matrix is a pose block coupled to
// independent 2x2 landmark blocks. Each iteration eliminates the landmarks first: given x, z_p
// has the marginal likelihood N(Hx_p x + ..., D_p), D_p = R + Hm_p P_p Hm_p^T, independent over
// p; the pose posterior is Sigma = Sigma_0 - Sigma_0 W (I + Sigma_0 W)^-1 Sigma_0 with
// W = sum Hx_p^T D_p^-1 Hx_p (valid for a singular Sigma_0), mean x0 + Sigma b with
// b = sum Hx_p^T D_p^-1 nu_p; each landmark is then the Kalman update of m_p given x (gain
// G_p = P_p Hm_p^T D_p^-1, residual nu_p - Hx_p (x - x0)). The stacked NIS is
// nu^T S^-1 nu = sum nu_p^T D_p^-1 nu_p - b^T Sigma b (Woodbury). A step costs O(M) instead of
// the O(M^3) of the stacked dense update, which it equals in real arithmetic (the dense update is
// the reference computation of datasets/phd2_density_test.cc). The PHD-SLAM 3.0 paper
// times 2.0b with the dense update; this implementation is not that cost model.
//
// Choices where the paper leaves room:
//  * Convergence: KL(previous || new) of the **pose marginals** below epsilon, from iteration 2,
//    as in docs/algorithms/phd-slam.md section 4.5. The pose marginal is what is sampled, and the
//    3-D test is the partitioned IPL's own, so both filters stop on the same criterion.
//  * Cholesky test: on the **joint** covariance (it is the next linearisation density); when it
//    is not positive definite the previous joint iterate is kept (the prior after a failure in
//    iteration 1). In arrow form the joint covariance is positive definite exactly when the pose
//    covariance and every C_p are, and the stacked S exactly when every D_p is: those are tested.
//  * No association (empty map, empty scan, or every component assigned to its misdetection
//    slot): the proposal is the prior N(mu_0, Sigma_0).
//  * Innovation guard (on by default in JointIplDensity, off in JointIplOptions): the removed
//    results script of the reference release ran "PHD 2.0b" through a predecessor routine with
//    an extra IPL stop rule on the accumulated normalised innovation squared
//    (docs/algorithms/phd-slam.md section 4.8). Without it the joint Gauss-Newton iterations
//    diverge whenever the best assignment pairs a clutter measurement with a near-field component
//    (a birth from clutter at ~1 m range gates almost any short-range measurement through Hx
//    Sigma_0 Hx^T, and relinearising that landmark makes the iterates jump by tens of metres); on
//    the paper scenario (N = 10, seeds 1-5, 4000 steps) the pooled position RMSE was about 65 m
//    without the guard and under 2 m with it (paper: 3.61 m). Here the guard tests the stacked NIS
//    at each iteration's linearisation against the chi-square quantile with tail probability
//    kPredecessorNisTailProbability and 2M degrees of freedom; reaching it stops the IPL and keeps
//    the previous iterate (the prior in iteration 1). Construct JointIplDensity(params, 0.0) for
//    the paper's description without the guard.
// Within one linearisation the pose marginal equals the partitioned IPL's result; the two differ
// only because the joint version also relinearises the landmarks.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "src/filters/importance_density.h"
#include "src/filters/ipl.h"

namespace phdslam::filters {

/// ChiSquareUpperQuantileEvenDof(dof, tail_probability) for one tail probability, each dof
/// computed once (the bisection costs hundreds of logarithms; the IPL asks at every call). Not
/// thread-safe: a density owns one, and a filter's density runs on one thread.
class EvenDofChiSquareQuantiles {
 public:
  /// Throws std::invalid_argument unless 0 < tail_probability < 1.
  explicit EvenDofChiSquareQuantiles(double tail_probability);
  /// Throws std::invalid_argument for an odd dof or dof < 2.
  double operator()(int dof);

 private:
  double tail_probability_;
  std::vector<double> by_half_dof_;  ///< NaN where not computed yet
};

struct JointIplOptions {
  int max_iterations = 5;      ///< L
  double kl_tolerance = 1e-3;  ///< epsilon, on the pose marginals
  /// Innovation guard of the predecessor code (docs/algorithms/phd-slam.md section 4.8), 0 = off
  /// (the paper's description). When > 0, an iteration whose stacked normalised innovation squared
  /// nu^T S^-1 nu, at its linearisation, reaches the chi-square quantile with this tail probability
  /// and 2M degrees of freedom stops the IPL, and the previous iterate is kept (the prior in
  /// iteration 1).
  double nis_tail_probability = 0.0;
  /// Optional memo of the quantiles for nis_tail_probability (EvenDofChiSquareQuantiles); when
  /// null, each call computes its quantile afresh (the same value).
  EvenDofChiSquareQuantiles* nis_quantiles = nullptr;
};

/// The joint posterior of the pose x and the landmarks m_1..m_M in arrow form: x ~ N(mean[0:3],
/// pose_cov) and, given x, independent m_p ~ N(mean_p + landmark_pose_coupling[p] (x - mean[0:3]),
/// landmark_conditional_cov[p]). O(M) to hold; JointCovariance() assembles the dense matrix.
struct JointIplResult {
  Eigen::VectorXd mean;  ///< [x; m_1; ...; m_M]
  Mat3 pose_covariance = Mat3::Zero();
  std::vector<Mat23> landmark_pose_coupling;   ///< F_p = dE[m_p | x] / dx
  std::vector<Mat2> landmark_conditional_cov;  ///< C_p = Cov(m_p | x)
  int iterations = 0;                          ///< iterations whose result was accepted
  bool cholesky_failed = false;
  bool nis_stopped = false;  ///< stopped by the innovation guard

  [[nodiscard]] Pose pose_mean() const { return mean.head<3>(); }
  [[nodiscard]] Mat3 pose_cov() const { return pose_covariance; }
  /// The dense (3 + 2M)^2 covariance: Cov(x, m_p) = pose_cov F_p^T,
  /// Cov(m_p, m_q) = F_p pose_cov F_q^T + [p = q] C_p. O(M^2); for tests and diagnostics.
  [[nodiscard]] Eigen::MatrixXd JointCovariance() const;
};

/// Joint IPL of the pose and the landmarks of `pairs` (see the file comment) from the pose prior
/// N(prior_mean, prior_cov) and the landmark priors of the pairs. With no pairs the result is the
/// pose prior with zero iterations.
JointIplResult JointIpl(const Pose& prior_mean, const Mat3& prior_cov,
                        std::span<const IplPair> pairs, const Mat2& noise_cov,
                        const JointIplOptions& options);

/// The x with P(chi2_dof > x) = tail_probability, for even dof >= 2 (closed-form survival
/// function, bisection to relative 1e-12). Throws std::invalid_argument otherwise.
double ChiSquareUpperQuantileEvenDof(int dof, double tail_probability);

/// Tail probability of the predecessor code's NIS stop rule (docs/algorithms/phd-slam.md section
/// 4.8).
inline constexpr double kPredecessorNisTailProbability = 1e-6;

class JointIplDensity final : public ImportanceDensity {
 public:
  /// Uses params.map.gate_threshold, params.ipl_iterations and params.ipl_kl_tolerance;
  /// nis_tail_probability > 0 enables the innovation guard (JointIplOptions), 0 disables it.
  explicit JointIplDensity(const PhdSlamParams& params,
                           double nis_tail_probability = kPredecessorNisTailProbability)
      : params_(params), nis_tail_probability_(nis_tail_probability) {
    if (nis_tail_probability > 0.0) nis_quantiles_.emplace(nis_tail_probability);
  }
  [[nodiscard]] ProposalOutput Build(const ProposalInput& input) const override;

 private:
  PhdSlamParams params_;
  double nis_tail_probability_;
  mutable std::optional<EvenDofChiSquareQuantiles> nis_quantiles_;  ///< when the guard is on
};

}  // namespace phdslam::filters
