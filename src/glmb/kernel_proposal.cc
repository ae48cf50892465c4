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

void UpdatePoseWithAssociation(const JointProblem& problem, const JointProblem::Parent& parent,
                               const Association& gamma, std::span<const Measurement> measurements,
                               const Mat2& noise_cov, Pose& mean, Mat3& cov) {
  for (std::size_t i = 0; i < parent.rows.size(); ++i) {
    const int g = gamma[i];
    if (g <= 0) continue;
    const TrackComponent& c = problem.entries[parent.rows[i]]->Heaviest();
    const models::RangeBearingJacobians jac = models::MeasurementJacobians(mean, c.mean);
    Vec2 nu = measurements[g - 1] - models::PredictMeasurement(mean, c.mean);
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
  for (std::size_t s : used) {
    Pose mu = mean;
    Mat3 sigma = cov;
    UpdatePoseWithAssociation(problem, problem.parents[samples[s].parent], samples[s].gamma,
                              measurements, noise_cov, mu, sigma);
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
