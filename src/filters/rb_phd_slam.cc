#include "src/filters/rb_phd_slam.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "src/core/gaussian.h"
#include "src/filters/pose_prediction.h"
#include "src/filters/resampling.h"

namespace phdslam::filters {

RbPhdSlam::RbPhdSlam(EstimatorContext context, PhdSlamParams params,
                     std::unique_ptr<ImportanceDensity> density, std::uint64_t stream_seed)
    : context_(std::move(context)),
      params_(std::move(params)),
      density_(std::move(density)),
      rng_(stream_seed) {
  const int n = std::max(1, params_.particles);
  particles_.resize(n);
  for (PhdParticle& p : particles_) {
    p.pose = context_.initial_pose;
    p.log_weight = -std::log(static_cast<double>(n));
    p.parent = 0;  // every particle starts as a copy of one parent
  }
}

double RbPhdSlam::EstimateThreshold() const {
  if (!std::isnan(params_.estimate_log_weight_threshold)) {
    return params_.estimate_log_weight_threshold;
  }
  const double q = 1.0 - context_.sensor.pd_nominal;
  return std::log(q * q);
}

void RbPhdSlam::Predict(PhdParticle& particle, const datasets::StepData& step) const {
  // Births at the pose the measurements were taken from, appended after existing components.
  if (!particle.births.empty()) {
    particle.map.AddBirths(particle.pose, particle.births, context_.sensor.noise_cov,
                           params_.map);
    particle.births.clear();
  }
  PredictPoseGaussian(context_, step, params_.pose_regularisation, particle.pose, particle.cov);
}

StepOutput RbPhdSlam::Step(const datasets::StepData& step) {
  const int n = static_cast<int>(particles_.size());
  // Association output: the best particle's top-ranked hypothesis, resolved to component means
  // of its map before the update.
  std::vector<std::vector<Landmark>> associated_means;
  // 1. The step's random numbers: one uniform and three standard normals per particle.
  std::vector<double> uniforms(n);
  std::vector<Vec3> normals(n);
  for (double& u : uniforms) u = rng_.Uniform();
  for (Vec3& xi : normals) xi << rng_.Normal(), rng_.Normal(), rng_.Normal();

  PreparedProposal proposal;
  int proposal_parent = -2;
  long hypotheses_total = 0;
  std::vector<int> particle_association_owner(n, -1);
  std::vector<std::vector<int>> associations;

  for (int idx = 0; idx < n; ++idx) {
    PhdParticle& p = particles_[idx];
    // 2.1 Predict.
    Predict(p, step);
    const Pose mu0 = p.pose;
    const Mat3 sigma0 = p.cov;
    // 2.2 Proposal, shared by consecutive copies of one parent.
    const bool reuse = params_.reuse_parent_proposal && p.parent >= 0 &&
                       p.parent == proposal_parent;
    if (!reuse) {
      ProposalInput input{mu0, sigma0, &p.map, step.measurements, &context_.sensor};
      ProposalOutput built = density_->Build(input);
      proposal = PrepareProposal(std::move(built.mixture));
      std::vector<Landmark> means;
      if (!built.best_association.empty()) {
        means.assign(built.best_association.size(), Landmark::Constant(std::nan("")));
        for (std::size_t j = 0; j < means.size(); ++j) {
          const int c = built.best_association[j];
          if (c >= 0) means[j] = p.map.active()[c].mean;
        }
      }
      associated_means.push_back(std::move(means));
      associations.push_back(std::move(built.best_association));
      proposal_parent = p.parent;
    }
    particle_association_owner[idx] = static_cast<int>(associations.size()) - 1;
    hypotheses_total += static_cast<long>(proposal.mixture.size());
    // 2.3 Sample and add log f - log q.
    const int t = PickComponent(proposal, uniforms[idx]);
    if (proposal.chol[t]) {
      const Pose x = proposal.mixture.means[t] + *proposal.chol[t] * normals[idx];
      // log f - log q, exactly 0 when the proposal is the prior itself (the bootstrap case).
      const bool is_prior = proposal.mixture.size() == 1 &&
                            proposal.mixture.means[0] == mu0 && proposal.mixture.covs[0] == sigma0;
      if (!is_prior) {
        const auto log_prior = LogNormalPdf<3>(x, mu0, sigma0);
        if (log_prior) p.log_weight += *log_prior - LogMixtureDensity(proposal, x);
      }
      p.pose = x;
    } else {
      p.pose = mu0;
    }
    p.cov.setZero();
    p.parent = -1;
    // 2.4 PHD update at the sampled pose.
    const phd::PhdUpdateResult update =
        p.map.Update(p.pose, step.measurements, context_.sensor, params_.map);
    p.log_weight += update.log_likelihood;
    p.births.clear();
    for (int j : update.ungated) p.births.push_back(step.measurements[j]);
    // 2.5 Hypothesis reduction and active/passive bookkeeping.
    p.map.Reduce(p.pose, context_.sensor, params_.map);
  }

  // 3. Estimate from the highest-weight particle (first on ties), before resampling.
  best_ = 0;
  for (int i = 1; i < n; ++i) {
    if (particles_[i].log_weight > particles_[best_].log_weight) best_ = i;
  }
  best_association_ = associations.empty() ? std::vector<int>{}
                                           : associations[particle_association_owner[best_]];
  last_map_ = particles_[best_].map.Estimate(EstimateThreshold());
  StepOutput out;
  out.pose = particles_[best_].pose;
  if (!associated_means.empty()) {
    out.association = std::move(associated_means[particle_association_owner[best_]]);
  }
  out.diag.map_components = static_cast<int>(particles_[best_].map.size());
  out.diag.hypotheses = static_cast<int>(std::lround(static_cast<double>(hypotheses_total) / n));

  // 4. ESS and resampling.
  std::vector<double> log_w(n);
  for (int i = 0; i < n; ++i) log_w[i] = particles_[i].log_weight;
  const std::vector<double> w = NormalisedWeights(log_w);
  if (n > 1) {
    Mat3 spread = Mat3::Zero();
    for (int i = 0; i < n; ++i) {
      const Vec3 d = particles_[i].pose - out.pose;
      spread += w[i] * d * d.transpose();
    }
    out.pose_cov = spread;
  }
  out.diag.ess = n == 1 ? 1.0 : EffectiveSampleSize(w);
  const double threshold = params_.ess_threshold_kind == EssThresholdKind::kRelative
                               ? params_.ess_threshold * n
                               : params_.ess_threshold;
  if (n > 1 && params_.resampling && out.diag.ess <= threshold) {
    std::vector<double> r(n);
    for (double& u : r) u = rng_.Uniform();
    const std::vector<int> sources = StratifiedResample(w, r);
    std::vector<PhdParticle> next;
    next.reserve(n);
    const double log_uniform = -std::log(static_cast<double>(n));
    for (int s : sources) {
      next.push_back(particles_[s]);
      next.back().log_weight = log_uniform;
      next.back().parent = s;
    }
    particles_ = std::move(next);
    out.diag.resampled = true;
  }
  return out;
}

MapEstimate RbPhdSlam::Map() const {
  MapEstimate m;
  for (const auto& c : last_map_) {
    m.means.push_back(c.mean);
    m.covs.push_back(c.cov);
    m.log_weights.push_back(c.log_weight);
  }
  return m;
}

std::vector<std::pair<Pose, double>> RbPhdSlam::ParticleStates() const {
  std::vector<std::pair<Pose, double>> states;
  states.reserve(particles_.size());
  for (const PhdParticle& p : particles_) states.emplace_back(p.pose, p.log_weight);
  return states;
}

}  // namespace phdslam::filters
