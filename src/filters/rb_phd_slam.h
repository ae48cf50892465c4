// Rao-Blackwellised PHD-SLAM: particles carry a pose and a GM-PHD map; the family members differ
// only in their ImportanceDensity (reference notes sections 6-14).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "src/core/random.h"
#include "src/filters/estimator.h"
#include "src/filters/importance_density.h"
#include "src/filters/phd_slam_params.h"
#include "src/phd/gm_phd_map.h"

namespace phdslam::filters {

struct PhdParticle {
  Pose pose = Pose::Zero();
  Mat3 cov = Mat3::Zero();      ///< non-zero only between prediction and sampling
  double log_weight = 0.0;
  int parent = 0;               ///< source index after resampling; -1: compute own proposal
  phd::GmPhdMap map;
  std::vector<Measurement> births;  ///< previous step's ungated measurements
};

class RbPhdSlam final : public OnlineEstimator {
 public:
  RbPhdSlam(EstimatorContext context, PhdSlamParams params,
            std::unique_ptr<ImportanceDensity> density, std::uint64_t stream_seed);

  StepOutput Step(const datasets::StepData& step) override;
  [[nodiscard]] MapEstimate Map() const override;
  [[nodiscard]] std::vector<std::pair<Pose, double>> ParticleStates() const override;

  [[nodiscard]] const std::vector<PhdParticle>& particles() const { return particles_; }
  /// Index (before resampling) of the particle the last estimate came from.
  [[nodiscard]] int best_particle() const { return best_; }
  /// The top-ranked association of the last step's best particle (measurement -> active component
  /// index before the update, -1 for none), when the importance density provides one.
  [[nodiscard]] const std::vector<int>& best_association() const { return best_association_; }

 private:
  void Predict(PhdParticle& particle, const datasets::StepData& step) const;
  double EstimateThreshold() const;

  EstimatorContext context_;
  PhdSlamParams params_;
  std::unique_ptr<ImportanceDensity> density_;
  RandomStream rng_;
  std::vector<PhdParticle> particles_;
  int best_ = 0;
  std::vector<int> best_association_;
  std::vector<phd::GaussianComponent> last_map_;  ///< best particle's estimate at the last step
};

}  // namespace phdslam::filters
