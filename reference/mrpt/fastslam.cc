#include "reference/mrpt/fastslam.h"

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/system/COutputLogger.h>

#include <cmath>
#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "reference/mrpt/fastslam_particle_set.h"
#include "src/core/gaussian.h"
#include "src/filters/particle_estimate.h"

namespace phdslam::reference {
namespace {

// MRPT's resampling draws from the process-wide mrpt::random::getRandomGenerator(). Every
// resampling in this file reseeds that generator from the estimator's own stream and draws under
// this lock, so its result depends only on the estimator's seed, whatever else runs in other
// threads (as long as nothing else in the process uses MRPT's global generator unlocked).
std::mutex& MrptGlobalGeneratorMutex() {
  static std::mutex mutex;
  return mutex;
}

mrpt::bayes::CParticleFilter::TParticleResamplingAlgorithm ToMrpt(ResamplingScheme s) {
  switch (s) {
    case ResamplingScheme::kMultinomial:
      return mrpt::bayes::CParticleFilter::prMultinomial;
    case ResamplingScheme::kResidual:
      return mrpt::bayes::CParticleFilter::prResidual;
    case ResamplingScheme::kStratified:
      return mrpt::bayes::CParticleFilter::prStratified;
    case ResamplingScheme::kSystematic:
      break;
  }
  return mrpt::bayes::CParticleFilter::prSystematic;
}

}  // namespace

struct FastSlam::MrptParts {
  MrptParts(const filters::EstimatorContext& context, const FastSlamOptions& options, int particles,
            RandomStream* rng)
      : set(context, options, particles, rng) {}
  mrpt::bayes::CParticleFilter filter;
  FastSlamParticleSet set;
};

FastSlam::FastSlam(filters::EstimatorContext context, int particles, std::uint64_t stream_seed,
                   FastSlamOptions options)
    : context_(std::move(context)),
      options_(std::move(options)),
      particles_(particles),
      stream_(stream_seed) {
  if (particles_ < 1) {
    throw std::invalid_argument("fastslam: expected at least one particle, got " +
                                std::to_string(particles_));
  }
  if (!context_.motion) throw std::invalid_argument("fastslam: the context has no motion model");
  options_.Validate();
  mrpt_ = std::make_unique<MrptParts>(context_, options_, particles_, &stream_);
  mrpt::bayes::CParticleFilter& pf = mrpt_->filter;
  pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
  auto& o = pf.m_options;
  o.PF_algorithm = options_.proposal == FastSlamProposal::kMotionModel
                       ? mrpt::bayes::CParticleFilter::pfStandardProposal
                       : mrpt::bayes::CParticleFilter::pfOptimalProposal;
  o.resamplingMethod = ToMrpt(options_.resampling);
  o.adaptiveSampleSize = false;
  o.sampleSize = static_cast<unsigned int>(particles_);
  o.powFactor = 1.0;
  // executeOn() must not resample: it calls performResampling() without the particle count, and
  // MRPT 2.5.8 then keeps the parents' log-weights on the copies instead of equal weights
  // (checked with MRPT 2.5.8). ESS() never drops below 0, so BETA = 0 disables it; Step()
  // resamples itself through performResampling(options, N).
  o.BETA = 0.0;
  best_.pose = context_.initial_pose;
}

FastSlam::~FastSlam() = default;

filters::StepOutput FastSlam::Step(const datasets::StepData& step) {
  FastSlamParticleSet& set = mrpt_->set;
  set.SetStep(&step, step_index_);
  mrpt_->filter.executeOn(set, nullptr, nullptr);
  set.SetStep(nullptr, step_index_);
  ++step_index_;

  // Estimate: the highest-weight particle (the first one on ties), before resampling.
  const std::size_t n = set.m_particles.size();
  best_ = set.m_particles[filters::HighestWeightIndex(set.m_particles,
                                                      [](const auto& p) { return p.log_w; })]
              .d;

  filters::StepOutput out;
  out.pose = best_.pose;
  out.diag.hypotheses = 1;
  out.diag.map_components = static_cast<int>(best_.landmarks.size());
  out.diag.ess = static_cast<double>(n) * set.ESS();
  out.diag.nis_sum = best_.nis.nis_sum;
  out.diag.nis_count = best_.nis.count;
  if (step.times.size() > 1) {
    std::vector<filters::PoseMoments> proposals;
    proposals.reserve(n);
    for (const auto& p : set.m_particles) proposals.push_back(p.d.proposal);
    if (const auto rb = filters::MatchMoments(proposals)) {
      out.pose_mean_rb = rb->mean;
      out.pose_cov_rb = rb->cov;
    }
  }
  if (n > 1) {
    // Weighted spread of the particle poses about their weighted mean (the log-weights are
    // normalised to max 0 by executeOn).
    std::vector<double> w(n);
    double sum = 0.0;
    Pose mean = Pose::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      w[i] = std::exp(set.m_particles[i].log_w);
      sum += w[i];
      mean += w[i] * set.m_particles[i].d.pose;
    }
    mean /= sum;
    for (double& wi : w) wi /= sum;
    Mat3 cov = filters::WeightedSpread(set.m_particles, w, mean,
                                       [](const auto& p) -> const Pose& { return p.d.pose; });
    Symmetrize(cov);
    out.pose_cov = cov;

    if (out.diag.ess <= options_.ess_threshold_fraction * static_cast<double>(n)) {
      const std::lock_guard<std::mutex> lock(MrptGlobalGeneratorMutex());
      mrpt::random::getRandomGenerator().randomize(static_cast<std::uint32_t>(stream_.NextU64()));
      set.performResampling(mrpt_->filter.m_options, n);
      out.diag.resampled = true;
    }
  }
  return out;
}

filters::MapEstimate FastSlam::Map() const {
  filters::MapEstimate map;
  for (const FastSlamLandmark& lm : best_.landmarks) {
    if (!lm.confirmed) continue;
    map.means.push_back(lm.mean);
    map.covs.push_back(lm.cov);
    map.log_weights.push_back(0.0);
  }
  return map;
}

}  // namespace phdslam::reference
