#include "reference/mrpt/fastslam_particle_set.h"

#include <mrpt/math/CMatrixDynamic.h>
#include <mrpt/slam/data_association.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <map>
#include <vector>

#include "reference/mrpt/motion_increment.h"
#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {
namespace {

/// A landmark of the particle's map that may have produced one of the measurements.
struct Candidate {
  std::size_t landmark = 0;
  Measurement predicted = Measurement::Zero();
  models::RangeBearingJacobians jacobians;
  Mat2 innovation_cov = Mat2::Identity();  ///< Hm P Hm^T + R (+ Hx Sigma0 Hx^T for FastSLAM 2.0)
};

mrpt::slam::TDataAssociationMethod ToMrpt(AssociationMethod m) {
  return m == AssociationMethod::kJcbb ? mrpt::slam::assocJCBB : mrpt::slam::assocNN;
}

mrpt::slam::TDataAssociationMetric ToMrpt(AssociationMetric m) {
  return m == AssociationMetric::kMatchingLikelihood ? mrpt::slam::metricML
                                                     : mrpt::slam::metricMaha;
}

/// MRPT's association between the measurements and the candidates' predictions. With
/// `pose_cov` set, the predictions are correlated through the pose (block (a, b) of their joint
/// covariance is Hx_a pose_cov Hx_b^T, plus Hm P Hm^T + R on the diagonal) and MRPT's
/// full-covariance routine is used; otherwise they are independent. The KD-tree candidate search
/// is off (see MrptEkfSlamOptions::mrpt_kdtree_candidates). MRPT subtracts bearings without
/// wrapping, which is exact while the FOV plus its buffer stays inside (-pi, pi).
/// Returns measurement index -> landmark index.
std::map<std::size_t, std::size_t> Associate(const std::vector<Measurement>& z,
                                             const std::vector<Candidate>& candidates,
                                             const Mat3* pose_cov, const FastSlamOptions& o) {
  if (z.empty() || candidates.empty()) return {};
  const auto n_obs = static_cast<Eigen::Index>(z.size());
  const auto n_pred = static_cast<Eigen::Index>(candidates.size());
  mrpt::math::CMatrixDouble z_means(n_obs, 2);
  for (Eigen::Index j = 0; j < n_obs; ++j) {
    z_means(j, 0) = z[static_cast<std::size_t>(j)](0);
    z_means(j, 1) = z[static_cast<std::size_t>(j)](1);
  }
  mrpt::math::CMatrixDouble y_means(n_pred, 2);
  std::vector<std::size_t> ids(candidates.size());
  for (Eigen::Index i = 0; i < n_pred; ++i) {
    const Candidate& c = candidates[static_cast<std::size_t>(i)];
    y_means(i, 0) = c.predicted(0);
    y_means(i, 1) = c.predicted(1);
    ids[static_cast<std::size_t>(i)] = c.landmark;
  }
  mrpt::slam::TDataAssociationResults results;
  if (pose_cov != nullptr) {
    mrpt::math::CMatrixDouble cov(2 * n_pred, 2 * n_pred);
    for (Eigen::Index a = 0; a < n_pred; ++a) {
      const Candidate& ca = candidates[static_cast<std::size_t>(a)];
      for (Eigen::Index b = 0; b < n_pred; ++b) {
        const Candidate& cb = candidates[static_cast<std::size_t>(b)];
        const Mat2 block = a == b ? ca.innovation_cov
                                  : Mat2(ca.jacobians.hx * *pose_cov * cb.jacobians.hx.transpose());
        cov.asEigen().block<2, 2>(2 * a, 2 * b) = block;
      }
    }
    mrpt::slam::data_association_full_covariance(
        z_means, y_means, cov, results, ToMrpt(o.association), ToMrpt(o.metric), o.ic_chi2_quantile,
        /*DAT_ASOC_USE_KDTREE=*/false, ids, mrpt::slam::metricMaha, 0.0);
  } else {
    mrpt::math::CMatrixDouble stacked(2 * n_pred, 2);
    for (Eigen::Index i = 0; i < n_pred; ++i) {
      stacked.asEigen().block<2, 2>(2 * i, 0) =
          candidates[static_cast<std::size_t>(i)].innovation_cov;
    }
    mrpt::slam::data_association_independent_predictions(
        z_means, y_means, stacked, results, ToMrpt(o.association), ToMrpt(o.metric),
        o.ic_chi2_quantile, /*DAT_ASOC_USE_KDTREE=*/false, ids, mrpt::slam::metricMaha, 0.0);
  }
  return {results.associations.begin(), results.associations.end()};
}

/// A draw from N(mean, cov) using the symmetric square root of cov (negative eigenvalues from
/// rounding are treated as zero, so a singular covariance is fine).
Pose SamplePose(const Pose& mean, const Mat3& cov, RandomStream& rng) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);
  const Vec3 sd = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Vec3 n(rng.Normal(), rng.Normal(), rng.Normal());
  return mean + eig.eigenvectors() * sd.asDiagonal() * n;
}

Measurement Residual(const Measurement& z, const Measurement& predicted) {
  return {z(0) - predicted(0), WrapAngle(z(1) - predicted(1))};
}

}  // namespace

FastSlamParticleSet::FastSlamParticleSet(const filters::EstimatorContext& context,
                                         const FastSlamOptions& options, int particles,
                                         RandomStream* rng)
    : context_(context), options_(options), rng_(rng) {
  new_landmark_log_likelihood_ = options_.new_landmark_log_likelihood.value_or(
      -std::log(2.0 * context_.sensor.fov_half_angle * context_.sensor.fov_range));
  m_particles.resize(static_cast<std::size_t>(particles));
  for (auto& p : m_particles) {
    p.log_w = 0.0;
    p.d.pose = context_.initial_pose;
  }
}

void FastSlamParticleSet::prediction_and_update_pfStandardProposal(
    const mrpt::obs::CActionCollection* /*action*/, const mrpt::obs::CSensoryFrame* /*observation*/,
    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& /*pf_options*/) {
  for (auto& p : m_particles) UpdateParticle(p.d, p.log_w, /*condition_on_measurements=*/false);
}

void FastSlamParticleSet::prediction_and_update_pfOptimalProposal(
    const mrpt::obs::CActionCollection* /*action*/, const mrpt::obs::CSensoryFrame* /*observation*/,
    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& /*pf_options*/) {
  for (auto& p : m_particles) UpdateParticle(p.d, p.log_w, /*condition_on_measurements=*/true);
}

void FastSlamParticleSet::UpdateParticle(FastSlamParticle& particle, double& log_w,
                                         bool condition_on_measurements) {
  const datasets::StepData& step = *step_;
  const models::SensorModel& sensor = context_.sensor;
  const Mat2& r = sensor.noise_cov;

  // Motion prior: the linearised transition density (docs/algorithms/models.md section 2.4), Q_n
  // added once.
  PoseGaussian prior{particle.pose, Mat3::Zero()};
  if (step.times.size() > 1) {
    prior.cov = options_.pose_regulariser_diag.asDiagonal();
    prior = PropagateOverStep(*context_.motion, context_.control_noise_cov, step, prior);
  }

  // FastSLAM 1.0 samples first and associates at the sampled pose; FastSLAM 2.0 associates at
  // the predicted mean with the pose uncertainty in the innovation covariances.
  Pose x = prior.mean;
  particle.proposal = {log_w, prior.mean, prior.cov};
  particle.nis = filters::InnovationStats{};
  if (!condition_on_measurements) x = SamplePose(prior.mean, prior.cov, *rng_);

  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < particle.landmarks.size(); ++i) {
    const FastSlamLandmark& lm = particle.landmarks[i];
    if (!sensor.InEnlargedFov(x, lm.mean)) continue;
    Candidate c;
    c.landmark = i;
    c.predicted = models::PredictMeasurement(x, lm.mean);
    c.jacobians = models::MeasurementJacobians(x, lm.mean);
    c.innovation_cov = c.jacobians.hm * lm.cov * c.jacobians.hm.transpose() + r;
    if (condition_on_measurements) {
      c.innovation_cov += c.jacobians.hx * prior.cov * c.jacobians.hx.transpose();
    }
    Symmetrize(c.innovation_cov);
    candidates.push_back(c);
  }
  const std::map<std::size_t, std::size_t> associations = Associate(
      step.measurements, candidates, condition_on_measurements ? &prior.cov : nullptr, options_);

  if (condition_on_measurements) {
    // Proposal: sequential EKF updates of the pose prior with the associated measurements,
    // relinearised at each updated mean; the weight is the product of the predictive likelihoods.
    Pose mu = prior.mean;
    Mat3 sigma = prior.cov;
    for (const auto& [j, i] : associations) {
      const FastSlamLandmark& lm = particle.landmarks[i];
      const auto jac = models::MeasurementJacobians(mu, lm.mean);
      Mat2 s = jac.hx * sigma * jac.hx.transpose() + jac.hm * lm.cov * jac.hm.transpose() + r;
      Symmetrize(s);
      const Measurement v = Residual(step.measurements[j], models::PredictMeasurement(mu, lm.mean));
      const Mat32 k = sigma * jac.hx.transpose() * s.inverse();
      mu += k * v;
      sigma -= k * s * k.transpose();
      Symmetrize(sigma);
      log_w += EvalGaussian2(v, s).log_pdf;
      particle.nis.Add(v, s);
    }
    particle.proposal.mean = mu;
    particle.proposal.cov = sigma;
    x = SamplePose(mu, sigma, *rng_);
  } else {
    for (const auto& [j, i] : associations) {
      const FastSlamLandmark& lm = particle.landmarks[i];
      const auto jac = models::MeasurementJacobians(x, lm.mean);
      Mat2 s = jac.hm * lm.cov * jac.hm.transpose() + r;
      Symmetrize(s);
      const Measurement v = Residual(step.measurements[j], models::PredictMeasurement(x, lm.mean));
      log_w += EvalGaussian2(v, s).log_pdf;
      particle.nis.Add(v, s);
    }
  }

  // Landmark EKF updates at the sampled pose.
  std::vector<bool> associated(particle.landmarks.size(), false);
  std::vector<bool> measurement_used(step.measurements.size(), false);
  for (const auto& [j, i] : associations) {
    FastSlamLandmark& lm = particle.landmarks[i];
    const auto jac = models::MeasurementJacobians(x, lm.mean);
    Mat2 s = jac.hm * lm.cov * jac.hm.transpose() + r;
    Symmetrize(s);
    const Mat2 k = lm.cov * jac.hm.transpose() * s.inverse();
    lm.mean += k * Residual(step.measurements[j], models::PredictMeasurement(x, lm.mean));
    lm.cov = (Mat2::Identity() - k * jac.hm) * lm.cov;
    Symmetrize(lm.cov);
    ++lm.counter;
    ++lm.associations;
    if (lm.associations >= options_.confirm_associations) lm.confirmed = true;
    associated[i] = true;
    measurement_used[j] = true;
  }

  // Existence counter: predicted visible but not associated counts against the landmark.
  for (std::size_t i = 0; i < particle.landmarks.size(); ++i) {
    FastSlamLandmark& lm = particle.landmarks[i];
    if (!associated[i] && sensor.DetectionProbability(x, lm.mean) > 0.0) --lm.counter;
  }
  std::erase_if(particle.landmarks, [&](const FastSlamLandmark& lm) {
    return lm.counter < 0 ||
           (!lm.confirmed && step_index_ - lm.birth_step >= options_.tentative_steps);
  });

  // Every measurement without a landmark creates one (inverse model at the sampled pose).
  for (std::size_t j = 0; j < step.measurements.size(); ++j) {
    if (measurement_used[j]) continue;
    FastSlamLandmark lm;
    lm.mean = models::InverseMeasurement(x, step.measurements[j]);
    lm.cov = models::BirthCovariance(x, step.measurements[j], r);
    lm.birth_step = step_index_;
    lm.confirmed = options_.confirm_associations == 0;
    particle.landmarks.push_back(lm);
    log_w += new_landmark_log_likelihood_;
  }
  particle.pose = x;
}

}  // namespace phdslam::reference
