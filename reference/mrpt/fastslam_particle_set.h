// FastSLAM particles as an MRPT particle filter object: CParticleFilterData stores the particles
// and weights, CParticleFilterDataImpl gives weights, ESS and resampling substitution, and the two
// prediction_and_update_* callbacks selected by CParticleFilter (pfStandardProposal for FastSLAM
// 1.0, pfOptimalProposal for FastSLAM 2.0) are implemented here. Internal to
// phdslam_reference_mrpt: this header includes MRPT.
#pragma once

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/bayes/CParticleFilterCapable.h>
#include <mrpt/bayes/CParticleFilterData.h>

#include <deque>

#include "datasets/scenario.h"
#include "reference/mrpt/fastslam_options.h"
#include "reference/mrpt/fastslam_particle.h"
#include "src/core/random.h"
#include "src/filters/estimator.h"

namespace phdslam::reference {

using FastSlamParticleData =
    mrpt::bayes::CParticleFilterData<FastSlamParticle, mrpt::bayes::particle_storage_mode::VALUE>;

class FastSlamParticleSet final
    : public FastSlamParticleData,
      public mrpt::bayes::CParticleFilterDataImpl<FastSlamParticleSet,
                                                  FastSlamParticleData::CParticleList> {
 public:
  /// `context`, `options` and `rng` must outlive the set. Every particle starts at the initial
  /// pose with an empty map and log-weight 0.
  FastSlamParticleSet(const filters::EstimatorContext& context, const FastSlamOptions& options,
                      int particles, RandomStream* rng);

  /// The inputs of the next CParticleFilter::executeOn call (which is given null MRPT
  /// action/observation pointers: the step travels in phdslam's own types, in double precision).
  void SetStep(const datasets::StepData* step, int step_index) {
    step_ = step;
    step_index_ = step_index;
  }

 protected:
  void prediction_and_update_pfStandardProposal(
      const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
      const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options) override;
  void prediction_and_update_pfOptimalProposal(
      const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
      const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options) override;

 private:
  /// Proposal, association, weight increment and map update of one particle.
  void UpdateParticle(FastSlamParticle& particle, double& log_w, bool condition_on_measurements);

  const filters::EstimatorContext& context_;
  const FastSlamOptions& options_;
  RandomStream* rng_;
  double new_landmark_log_likelihood_;
  const datasets::StepData* step_ = nullptr;
  int step_index_ = 0;
};

}  // namespace phdslam::reference
