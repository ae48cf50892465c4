#include "oracle/oracle_rbpf.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/filters/pose_prediction.h"
#include "src/filters/ipl.h"
#include "src/filters/resampling.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::oracle {
namespace {

// Checks the labels and returns the number of landmark slots (largest index + 1).
int CheckOrigins(const std::vector<std::vector<int>>& origins) {
  int max_index = -1;
  for (std::size_t k = 0; k < origins.size(); ++k) {
    std::vector<int> seen;
    for (std::size_t j = 0; j < origins[k].size(); ++j) {
      const int o = origins[k][j];
      if (o < datasets::kClutter) {
        throw std::invalid_argument(
            "oracle RBPF: step " + std::to_string(k) + ", measurement " + std::to_string(j) +
            ": origin label " + std::to_string(o) +
            " is not a landmark index (>= 0) or clutter (-1); the oracle needs known "
            "origins and cannot run on real data such as Victoria Park");
      }
      if (o >= 0) seen.push_back(o);
      max_index = std::max(max_index, o);
    }
    std::sort(seen.begin(), seen.end());
    const auto dup = std::adjacent_find(seen.begin(), seen.end());
    if (dup != seen.end()) {
      throw std::invalid_argument("oracle RBPF: step " + std::to_string(k) + " measures landmark " +
                                  std::to_string(*dup) +
                                  " more than once; expected at most one measurement per "
                                  "landmark and scan");
    }
  }
  return max_index + 1;
}

}  // namespace

void OracleParams::Validate() const {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("oracle parameters: " + what);
  };
  if (particles < 1) fail("particles must be >= 1, got " + std::to_string(particles));
  if (!(ess_threshold >= 0.0) || !std::isfinite(ess_threshold)) {
    fail("ess_threshold must be finite and >= 0, got " + std::to_string(ess_threshold));
  }
  if (ipl_iterations < 1) {
    fail("ipl_iterations must be >= 1, got " + std::to_string(ipl_iterations));
  }
  if (!(ipl_kl_tolerance >= 0.0) || !std::isfinite(ipl_kl_tolerance)) {
    fail("ipl_kl_tolerance must be finite and >= 0, got " + std::to_string(ipl_kl_tolerance));
  }
  if (!pose_regularisation.allFinite() ||
      !pose_regularisation.isApprox(pose_regularisation.transpose(), 0.0)) {
    fail("pose_regularisation must be finite and symmetric");
  }
}

OracleRbpf::OracleRbpf(filters::EstimatorContext context, std::vector<std::vector<int>> origins,
                       OracleParams params, std::uint64_t stream_seed)
    : context_(std::move(context)),
      origins_(std::move(origins)),
      params_(std::move(params)),
      rng_(stream_seed) {
  params_.Validate();
  if (!context_.motion) throw std::invalid_argument("oracle RBPF: the context has no motion model");
  const int landmark_slots = CheckOrigins(origins_);
  particles_.resize(params_.particles);
  for (OracleParticle& p : particles_) {
    p.pose = context_.initial_pose;
    p.log_weight = -std::log(static_cast<double>(params_.particles));
    p.landmarks.resize(landmark_slots);
  }
}

std::unique_ptr<OracleRbpf> OracleRbpf::FromScenario(const datasets::Scenario& scenario,
                                                     OracleParams params,
                                                     std::uint64_t stream_seed) {
  std::vector<std::vector<int>> origins;
  origins.reserve(scenario.steps.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    const datasets::ScenarioStep& s = scenario.steps[k];
    if (s.origin.size() != s.data.measurements.size()) {
      throw std::invalid_argument(
          "oracle RBPF: scenario '" + scenario.name + "' step " + std::to_string(k) + " has " +
          std::to_string(s.data.measurements.size()) + " measurements but " +
          std::to_string(s.origin.size()) + " origin labels; the oracle needs every origin");
    }
    origins.push_back(s.origin);
  }
  try {
    return std::make_unique<OracleRbpf>(filters::EstimatorContext::FromScenario(scenario),
                                        std::move(origins), std::move(params), stream_seed);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("scenario '" + scenario.name + "': " + e.what());
  }
}

void OracleRbpf::Predict(OracleParticle& particle, const datasets::StepData& step) const {
  PredictPoseGaussian(context_, step, params_.pose_regularisation, particle.pose, particle.cov);
}

filters::StepOutput OracleRbpf::Step(const datasets::StepData& step) {
  if (step_index_ >= origins_.size()) {
    throw std::invalid_argument("oracle RBPF: step " + std::to_string(step_index_) +
                                " has no origin labels (only " + std::to_string(origins_.size()) +
                                " steps were given)");
  }
  const std::vector<int>& origin = origins_[step_index_];
  if (origin.size() != step.measurements.size()) {
    throw std::invalid_argument("oracle RBPF: step " + std::to_string(step_index_) + " has " +
                                std::to_string(step.measurements.size()) + " measurements but " +
                                std::to_string(origin.size()) + " origin labels");
  }
  ++step_index_;
  const int n = static_cast<int>(particles_.size());
  const int nz = static_cast<int>(step.measurements.size());

  // Landmark measurements in ascending landmark order (the IPL's sequential order).
  std::vector<int> by_landmark;
  for (int j = 0; j < nz; ++j) {
    if (origin[j] >= 0) by_landmark.push_back(j);
  }
  std::sort(by_landmark.begin(), by_landmark.end(),
            [&origin](int a, int b) { return origin[a] < origin[b]; });

  // 1. The step's random numbers, laid out as in RbPhdSlam.
  std::vector<double> uniforms(n);
  std::vector<Vec3> normals(n);
  for (double& u : uniforms) u = rng_.Uniform();
  for (Vec3& xi : normals) xi << rng_.Normal(), rng_.Normal(), rng_.Normal();

  const Mat2& r_cov = context_.sensor.noise_cov;
  const filters::IplOptions ipl_options{params_.ipl_iterations, params_.ipl_kl_tolerance};
  const Landmark nan_landmark = Landmark::Constant(std::numeric_limits<double>::quiet_NaN());
  std::vector<std::vector<Landmark>> associations(n);
  std::vector<filters::IplPair> pairs;
  std::vector<int> pair_measurements;

  for (int idx = 0; idx < n; ++idx) {
    OracleParticle& p = particles_[idx];
    // 2a. Predict.
    Predict(p, step);
    const Pose mu0 = p.pose;
    const Mat3 sigma0 = p.cov;
    // 2b. Proposal over the re-observed landmarks.
    pairs.clear();
    pair_measurements.clear();
    std::vector<Landmark>& assoc = associations[idx];
    assoc.assign(nz, nan_landmark);
    for (int j : by_landmark) {
      const OracleLandmark& lm = p.landmarks[origin[j]];
      if (!lm.seen) continue;
      pairs.push_back({lm.mean, lm.cov, step.measurements[j]});
      pair_measurements.push_back(j);
      assoc[j] = lm.mean;
    }
    Pose proposal_mean = mu0;
    Mat3 proposal_cov = sigma0;
    bool proposal_is_prior = true;
    if (!pairs.empty()) {
      const filters::IplResult ipl =
          filters::PartitionedIpl(mu0, sigma0, pairs, r_cov, ipl_options);
      if (ipl.iterations > 0) {
        proposal_mean = ipl.mean;
        proposal_cov = ipl.cov;
        proposal_is_prior = false;
      }
    }
    // 2c. Sample and add log f - log q.
    const auto chol = CholeskyLower<3>(proposal_cov);
    if (chol) {
      const Pose x = proposal_mean + *chol * normals[idx];
      if (!proposal_is_prior) {
        const auto log_prior = LogNormalPdf<3>(x, mu0, sigma0);
        const auto log_q = LogNormalPdf<3>(x, proposal_mean, proposal_cov);
        if (log_prior && log_q) p.log_weight += *log_prior - *log_q;
      }
      p.pose = x;
    } else {
      p.pose = mu0;
    }
    p.cov.setZero();
    // 2d. Landmark likelihoods and EKF updates at the sampled pose, then first sightings.
    for (int j : pair_measurements) {
      OracleLandmark& lm = p.landmarks[origin[j]];
      const auto jac = models::MeasurementJacobians(p.pose, lm.mean);
      Vec2 nu = step.measurements[j] - models::PredictMeasurement(p.pose, lm.mean);
      nu(1) = WrapAngle(nu(1));
      const Mat2 pht = lm.cov * jac.hm.transpose();
      Mat2 s = jac.hm * pht + r_cov;
      Symmetrize(s);
      const auto log_lik = LogNormalPdf<2>(nu, Vec2::Zero(), s);
      if (log_lik) p.log_weight += *log_lik;
      const Mat2 k = pht * s.inverse();
      lm.mean += k * nu;
      lm.cov -= k * s * k.transpose();
      Symmetrize(lm.cov);
    }
    for (int j : by_landmark) {
      OracleLandmark& lm = p.landmarks[origin[j]];
      if (lm.seen) continue;
      lm.mean = models::InverseMeasurement(p.pose, step.measurements[j]);
      lm.cov = models::BirthCovariance(p.pose, step.measurements[j], r_cov);
      lm.seen = true;
    }
  }

  // 3. Estimate from the highest-weight particle (first on ties), before resampling.
  best_ = 0;
  for (int i = 1; i < n; ++i) {
    if (particles_[i].log_weight > particles_[best_].log_weight) best_ = i;
  }
  const OracleParticle& best = particles_[best_];
  best_landmarks_ = best.landmarks;
  filters::StepOutput out;
  out.pose = best.pose;
  out.association = std::move(associations[best_]);
  out.diag.hypotheses = 1;
  out.diag.map_components =
      static_cast<int>(std::count_if(best.landmarks.begin(), best.landmarks.end(),
                                     [](const OracleLandmark& lm) { return lm.seen; }));

  // 4. ESS and resampling.
  std::vector<double> log_w(n);
  for (int i = 0; i < n; ++i) log_w[i] = particles_[i].log_weight;
  const std::vector<double> w = filters::NormalisedWeights(log_w);
  if (n > 1) {
    Mat3 spread = Mat3::Zero();
    for (int i = 0; i < n; ++i) {
      const Vec3 d = particles_[i].pose - out.pose;
      spread += w[i] * d * d.transpose();
    }
    out.pose_cov = spread;
  }
  out.diag.ess = n == 1 ? 1.0 : filters::EffectiveSampleSize(w);
  if (n > 1 && params_.resampling && out.diag.ess <= params_.ess_threshold * n) {
    std::vector<double> r(n);
    for (double& u : r) u = rng_.Uniform();
    const std::vector<int> sources = filters::StratifiedResample(w, r);
    std::vector<OracleParticle> next;
    next.reserve(n);
    const double log_uniform = -std::log(static_cast<double>(n));
    for (int s : sources) {
      next.push_back(particles_[s]);
      next.back().log_weight = log_uniform;
    }
    particles_ = std::move(next);
    out.diag.resampled = true;
  }
  return out;
}

filters::MapEstimate OracleRbpf::Map() const {
  filters::MapEstimate m;
  for (const OracleLandmark& lm : best_landmarks_) {
    if (!lm.seen) continue;
    m.means.push_back(lm.mean);
    m.covs.push_back(lm.cov);
    m.log_weights.push_back(0.0);
  }
  return m;
}

}  // namespace phdslam::oracle
