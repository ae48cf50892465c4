// delta-GLMB-SLAM 2.0 (glmb2), delta-GLMB-SLAM 1.0 (glmb1) and LMB-SLAM (lmb) of Moratuwage,
// Adams & Inostroza (Sensors 2019) on the suite's particle-filter skeleton
// (filters/particle_filter.h): each particle holds a pose and a labelled map.
//
//  - glmb1: GlmbMapModel with the transition density (docs/algorithms/glmb-slam.md section 6.2):
//    x_k ~ N(f(x_{k-1}, u), Sigma_0) and the weight w * Z-hat(x_k) of the joint update
//    (joint_update.h) at x_k.
//  - glmb2: GlmbMapModel with its own optimal-kernel proposal (docs/algorithms/glmb-slam.md section
//    6.3, kernel_proposal.h): the joint problem at the predicted mean x-hat with H_x Sigma_0 H_x'
//    in every innovation covariance is Gibbs-sampled, each (hypothesis, association) updates
//    N(x-hat, Sigma_0) by an EKF, and the weighted updates are collapsed (kernel_form) and sampled;
//    the joint update is then run again, independently, at the sampled pose (A5). Weight:
//    kernel_weight (A4).
//  - lmb: LmbMapModel (docs/algorithms/glmb-slam.md section 7): each update converts the LMB
//    (in-FOV tracks, existence p_S r) into one delta-GLMB hypothesis, runs the same joint update
//    with all Gibbs samples on it, converts back (glmb2lmb), prunes r < existence_prune_threshold,
//    caps at max_tracks and reduces each track's mixture; no measurement clustering. Out-of-FOV
//    tracks are untouched.
//
// Common to the three (each option in glmb_slam_params.h with its default):
//  - p_D is the sensor's at the entry's (heaviest component's) mean, the FOV a point test there;
//    p_S = survival_probability inside the FOV and 1 outside; out-of-FOV entries pass through;
//  - kappa = Lambda pdf_c with pdf_c per clutter_space, Lambda the sensor's clutter rate (at
//    least SensorModel::kMinFilterClutterRate); gating at gate_probability;
//  - births after each update from every measurement of the scan at the sampled pose, labelled
//    (k + 1, j), r_B by birth_rule; the update runs on empty scans too;
//  - Gibbs sampling (gibbs_samples per particle, shared out by sqrt of the hypothesis weights)
//    from the optimal association (optimal_start), pruning at hypothesis_prune_threshold, cap
//    max_hypotheses;
//  - estimate: the skeleton's highest-weight particle (before resampling) gives the pose and its
//    MAP-cardinality hypothesis the map (docs/algorithms/glmb-slam.md section 8), LMB: the top-N
//    tracks by r;
//  - resampling every step (the paper) or at the suite's ESS threshold (resampling);
//  - the RB pose covariance is the skeleton's (the proposal's moments: the predicted Gaussian
//    for glmb1 and lmb, the kernel for glmb2); NIS: the detections of the best particle's
//    highest-weight posterior hypothesis, with the S of its update.
// Random numbers: the skeleton's stream for poses and resampling, and for the Gibbs sampler a
// second stream seeded from the same stream seed (DeriveSeed(seed, HashName("glmb-gibbs"))),
// drawn in particle order, so results do not depend on threads.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "src/core/random.h"
#include "src/filters/estimator.h"
#include "src/filters/particle_filter.h"
#include "src/glmb/birth.h"
#include "src/glmb/glmb_density.h"
#include "src/glmb/glmb_slam_params.h"
#include "src/glmb/joint_update.h"
#include "src/glmb/lmb.h"
#include "src/phd/gaussian_component.h"

namespace phdslam::glmb {

/// What the three filters share: the per-step update settings and the Gibbs stream.
class LabelledMapCommon {
 public:
  LabelledMapCommon(const filters::EstimatorContext& context, const GlmbSlamParams& params,
                    std::uint64_t stream_seed);
  [[nodiscard]] const UpdateSettings& settings() const { return settings_; }
  [[nodiscard]] const MeasurementSetup& setup() const { return setup_; }
  [[nodiscard]] const GlmbSlamParams& params() const { return params_; }
  [[nodiscard]] RandomStream& rng() const { return *rng_; }

 private:
  GlmbSlamParams params_;
  std::shared_ptr<const models::SensorModel> sensor_;  ///< stable address for setup_.sensor
  UpdateSettings settings_;
  MeasurementSetup setup_;
  std::unique_ptr<RandomStream> rng_;
};

/// A delta-GLMB particle map.
struct GlmbParticleMap {
  std::vector<Hypothesis> hypotheses = EmptyDensity();
  std::vector<BirthTrack> births;  ///< from the previous scan, offered to the next update
  std::uint64_t next_id = 1;
  int updates = 0;
};

class GlmbMapModel {
 public:
  using Map = GlmbParticleMap;
  using Snapshot = filters::MapEstimate;

  GlmbMapModel(const filters::EstimatorContext& context, const GlmbSlamParams& params,
               bool optimal_kernel, std::uint64_t stream_seed);

  [[nodiscard]] Map InitialMap() const { return {}; }
  void BeginStep(const StepData& /*step*/) {}
  void BeforePrediction(Map& /*map*/, const Pose& /*pose*/) const {}
  /// The entries of the highest-weight hypothesis.
  [[nodiscard]] filters::MapView View(const Map& map);
  /// glmb2's kernel proposal; nullopt for glmb1 (the transition density).
  [[nodiscard]] std::optional<filters::ProposalOutput> Propose(
      const Map& map, const filters::ProposalInput& input) const;
  void Update(Map& map, const Pose& pose, const StepData& step, double& log_weight,
              filters::InnovationStats& nis) const;
  [[nodiscard]] Snapshot Estimate(const Map& map) const;
  [[nodiscard]] filters::MapEstimate ToMapEstimate(const Snapshot& s) const { return s; }
  /// The number of hypotheses.
  [[nodiscard]] int ComponentCount(const Map& map) const {
    return static_cast<int>(map.hypotheses.size());
  }

 private:
  LabelledMapCommon common_;
  bool optimal_kernel_;
  std::vector<phd::GaussianComponent> view_;
};

/// An LMB particle map.
struct LmbParticleMap {
  std::vector<Bernoulli> tracks;  ///< label order
  std::vector<BirthTrack> births;
  std::uint64_t next_id = 1;
  int updates = 0;
};

class LmbMapModel {
 public:
  using Map = LmbParticleMap;
  using Snapshot = filters::MapEstimate;

  LmbMapModel(const filters::EstimatorContext& context, const GlmbSlamParams& params,
              std::uint64_t stream_seed);

  [[nodiscard]] Map InitialMap() const { return {}; }
  void BeginStep(const StepData& /*step*/) {}
  void BeforePrediction(Map& /*map*/, const Pose& /*pose*/) const {}
  /// Every track, log-weight log r.
  [[nodiscard]] filters::MapView View(const Map& map);
  void Update(Map& map, const Pose& pose, const StepData& step, double& log_weight,
              filters::InnovationStats& nis) const;
  [[nodiscard]] Snapshot Estimate(const Map& map) const;
  [[nodiscard]] filters::MapEstimate ToMapEstimate(const Snapshot& s) const { return s; }
  /// The number of tracks.
  [[nodiscard]] int ComponentCount(const Map& map) const {
    return static_cast<int>(map.tracks.size());
  }

 private:
  LabelledMapCommon common_;
  std::vector<phd::GaussianComponent> view_;
};

using GlmbSlam = filters::ParticleFilter<GlmbMapModel>;
using LmbSlam = filters::ParticleFilter<LmbMapModel>;

/// glmb2 (optimal_kernel) or glmb1.
std::unique_ptr<GlmbSlam> MakeGlmbSlam(filters::EstimatorContext context,
                                       const GlmbSlamParams& params, bool optimal_kernel,
                                       std::uint64_t stream_seed);
std::unique_ptr<LmbSlam> MakeLmbSlam(filters::EstimatorContext context,
                                     const GlmbSlamParams& params, std::uint64_t stream_seed);

}  // namespace phdslam::glmb

extern template class phdslam::filters::ParticleFilter<phdslam::glmb::GlmbMapModel>;
extern template class phdslam::filters::ParticleFilter<phdslam::glmb::LmbMapModel>;
