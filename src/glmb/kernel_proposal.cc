#include "src/glmb/kernel_proposal.h"

#include <Eigen/LU>
#include <algorithm>
#include <vector>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/filters/pose_mixture_moments.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::glmb {

namespace {

/// One detected row of UpdatePoseWithAssociation: entry `track` detected by z.
void UpdatePoseWithDetection(const Track& track, const Measurement& z, const Mat2& noise_cov,
                             Pose& mean, Mat3& cov) {
  const TrackComponent& c = track.Heaviest();
  const models::RangeBearingJacobians jac = models::MeasurementJacobians(mean, c.mean);
  Vec2 nu = z - models::PredictMeasurement(mean, c.mean);
  nu(1) = WrapAngle(nu(1));
  Mat2 noise = jac.hm * c.cov * jac.hm.transpose() + noise_cov;
  Symmetrize(noise);
  Mat2 s = jac.hx * cov * jac.hx.transpose() + noise;
  Symmetrize(s);
  const Mat32 k = cov * jac.hx.transpose() * s.inverse();
  const Mat3 a = Mat3::Identity() - k * jac.hx;
  mean += k * nu;
  cov = a * cov * a.transpose() + k * noise * k.transpose();
  Symmetrize(cov);
}

/// UpdatePoseWithAssociation for a sequence of samples, each resuming from the states its
/// predecessor passed through on the rows the two share (the same parent and the same values on
/// rows [0, L)): the same updates in the same order, so the same poses bit for bit. A parent's
/// distinct samples come in lexicographic order, so that neighbours share their first rows.
class PoseUpdatesByPrefix {
 public:
  PoseUpdatesByPrefix(const JointProblem& problem, std::span<const Measurement> measurements,
                      const Mat2& noise_cov, const Pose& mean, const Mat3& cov)
      : problem_(problem), measurements_(measurements), noise_cov_(noise_cov) {
    states_.push_back(State{mean, cov});
  }

  /// The updated pose of `sample` into mean and cov.
  void Update(const SampledAssociation& sample, Pose& mean, Mat3& cov) {
    const JointProblem::Parent& parent = problem_.parents[sample.parent];
    const std::span<const int> gamma = sample.gamma;
    std::size_t shared = 0;
    if (sample.parent == last_parent_) {
      while (shared < gamma.size() && gamma[shared] == last_gamma_[shared]) ++shared;
    }
    // after_[i]: the number of updates through row i of the last sample; states_[k] the state
    // after k of them.
    const std::size_t done = shared > 0 ? after_[shared - 1] : 0;
    states_.resize(done + 1);
    after_.resize(gamma.size());
    for (std::size_t i = shared; i < gamma.size(); ++i) {
      const int g = gamma[i];
      if (g > 0) {
        State next = states_.back();
        UpdatePoseWithDetection(*problem_.entries[parent.rows[i]], measurements_[g - 1], noise_cov_,
                                next.mean, next.cov);
        states_.push_back(next);
      }
      after_[i] = states_.size() - 1;
    }
    last_parent_ = sample.parent;
    last_gamma_ = gamma;
    mean = states_.back().mean;
    cov = states_.back().cov;
  }

 private:
  struct State {
    Pose mean;
    Mat3 cov;
  };
  const JointProblem& problem_;
  std::span<const Measurement> measurements_;
  const Mat2& noise_cov_;
  std::vector<State> states_;
  std::vector<std::size_t> after_;
  int last_parent_ = -1;
  std::span<const int> last_gamma_;  ///< a view of the last sample's values
};

}  // namespace

void UpdatePoseWithAssociation(const JointProblem& problem, const JointProblem::Parent& parent,
                               std::span<const int> gamma,
                               std::span<const Measurement> measurements, const Mat2& noise_cov,
                               Pose& mean, Mat3& cov) {
  for (std::size_t i = 0; i < parent.rows.size(); ++i) {
    const int g = gamma[i];
    if (g <= 0) continue;
    UpdatePoseWithDetection(*problem.entries[parent.rows[i]], measurements[g - 1], noise_cov, mean,
                            cov);
  }
}

KernelProposal BuildKernelProposal(const JointProblem& problem,
                                   std::span<const SampledAssociation> samples, const Pose& mean,
                                   const Mat3& cov, std::span<const Measurement> measurements,
                                   const Mat2& noise_cov, KernelAssociations associations,
                                   KernelForm form) {
  KernelProposal out;
  if (samples.empty()) {
    out.mixture.Add(0.0, mean, cov);
    out.log_marginal = kNegInf;
    return out;
  }
  std::vector<double> log_w;
  log_w.reserve(samples.size());
  for (const SampledAssociation& s : samples) log_w.push_back(s.log_weight);
  out.log_marginal = LogSumExp(log_w);
  std::vector<std::size_t> used;
  if (associations == KernelAssociations::kBest) {
    used.push_back(
        static_cast<std::size_t>(std::max_element(log_w.begin(), log_w.end()) - log_w.begin()));
  } else {
    for (std::size_t s = 0; s < samples.size(); ++s) used.push_back(s);
  }
  std::vector<filters::PoseMoments> parts;
  parts.reserve(used.size());
  PoseUpdatesByPrefix updates(problem, measurements, noise_cov, mean, cov);
  for (std::size_t s : used) {
    Pose mu;
    Mat3 sigma;
    updates.Update(samples[s], mu, sigma);
    parts.push_back(filters::PoseMoments{log_w[s] - out.log_marginal, mu, sigma});
  }
  if (form == KernelForm::kMixture || parts.size() == 1) {
    for (const filters::PoseMoments& p : parts) out.mixture.Add(p.log_weight, p.mean, p.cov);
    return out;
  }
  const std::optional<filters::PoseMoments> m = filters::MatchMoments(parts);
  if (m) {
    out.mixture.Add(0.0, m->mean, m->cov);
  } else {
    out.mixture.Add(0.0, mean, cov);
  }
  return out;
}

}  // namespace phdslam::glmb
