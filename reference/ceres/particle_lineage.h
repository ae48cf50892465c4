// The ancestral path of a particle filter's particles (README.md, "Start from another estimator's
// trajectory"). A particle filter's estimate at each step is its highest-weight particle of that
// step; from step to step it can switch between particles whose trajectories lie metres apart,
// so the sequence of estimates jumps where no particle ever moved. Each particle's own path, its
// pose at every step traced back through the resampling ancestry, is continuous: it is the
// trajectory the particle's map was built along. The path of the particle with the highest weight
// at the last step is the filter's own choice of one trajectory for the whole run.
#pragma once

#include <cstddef>
#include <vector>

#include "src/core/types.h"
#include "src/filters/particle_filter.h"

namespace phdslam::reference {

/// What a particle filter's steps leave for the lineage: every particle's pose and log-weight
/// after its update (before resampling) and, where the step resampled, the source index of every
/// new particle. Particle j of a step descends from particle j after the previous step's
/// resampling (ParticleFilter keeps the index), i.e. from particle sources[j] before it.
class ParticleLineage {
 public:
  /// Particle `idx` of step `step` after its update. Steps must come in order from 0, and each
  /// step's particles from 0; throws std::invalid_argument otherwise.
  void AddParticle(int step, int idx, const Pose& pose, double log_weight);
  /// The step resampled: new particle j is a copy of particle sources[j] of that step. Throws
  /// std::invalid_argument when the step is not the last one recorded or an index is outside its
  /// particles.
  void AddResampling(int step, const std::vector<int>& sources);

  [[nodiscard]] std::size_t steps() const { return poses_.size(); }

  /// The path, one pose per recorded step, of the particle with the highest log-weight at the
  /// last step (the first on ties, as the filter's estimate). Empty when nothing is recorded;
  /// throws std::logic_error when a step's particle count does not match its ancestry.
  [[nodiscard]] std::vector<Pose> BestFinalPath() const;

 private:
  std::vector<std::vector<Pose>> poses_;
  std::vector<std::vector<double>> log_weights_;
  std::vector<std::vector<int>> sources_;  ///< empty: the step did not resample
};

/// Whatever records a ParticleLineage, seen without its particle type.
class LineageSource {
 public:
  virtual ~LineageSource() = default;
  [[nodiscard]] virtual const ParticleLineage& lineage() const = 0;
};

/// A filters::StepObserver that records the ParticleLineage of a ParticleFilter
/// (ParticleFilter::SetObserver).
template <class ParticleType>
class LineageObserver final : public filters::StepObserver<ParticleType>, public LineageSource {
 public:
  void Sampled(int /*step*/, int /*idx*/, const Pose& /*mu0*/, const Mat3& /*sigma0*/,
               const filters::PreparedProposal& /*proposal*/, const ParticleType& /*p*/) override {}
  void Updated(int step, int idx, const ParticleType& p) override {
    lineage_.AddParticle(step, idx, p.pose, p.log_weight);
  }
  void Resampled(int step, const std::vector<int>& sources) override {
    lineage_.AddResampling(step, sources);
  }
  [[nodiscard]] const ParticleLineage& lineage() const override { return lineage_; }

 private:
  ParticleLineage lineage_;
};

}  // namespace phdslam::reference
