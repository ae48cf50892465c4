// The oracle RBPF: FastSLAM 2.0 with known data association and the partitioned IPL proposal
// (docs/algorithms/oracle.md). It is the particle-filter skeleton (src/filters/particle_filter.h)
// over per-landmark EKFs; it differs from PHD-SLAM only in where its association comes from: it
// reads the scenario's hidden origin labels, and it serves as the accuracy bound the PHD-SLAM
// filters are compared with.
//
// Per step and particle (the skeleton's order and random-number layout):
//   - proposal (known_association_density.h): the partitioned IPL from the predicted Gaussian over
//     the measurements of landmarks this particle has seen before, in ascending landmark order;
//     the prior when there are none;
//   - update: for each re-observed landmark add log N(z; h(m, x), Hm P Hm^T + R) (bearing residual
//     wrapped) and apply the EKF update at x; initialise first sightings with the inverse model at
//     x (covariance G R G^T);
//   - consistency outputs: the Rao-Blackwellised pose covariance is the mixture over particles of
//     their partitioned-IPL proposals (the prior for a particle without re-observed landmarks)
//     with the carried-in weights (particle_filter.h); NIS per re-observed landmark with the S of
//     its likelihood term, for the estimate's particle;
//   - proposals are not shared between copies of one parent (reuse_parent_proposal is off).
// Clutter measurements are discarded and missed detections are simply absent, so neither touches
// the weights or the random stream: removing clutter from a scenario leaves the result unchanged.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/types.h"
#include "src/filters/estimator.h"
#include "src/filters/innovation_stats.h"
#include "src/filters/particle_filter.h"
#include "src/phd/gaussian_component.h"

namespace phdslam::oracle {

struct OracleParams {
  int particles = 1;
  bool resampling = true;
  double ess_threshold = 0.2;  ///< resample when ESS <= ess_threshold * N
  int ipl_iterations = 5;      ///< L
  double ipl_kl_tolerance = 1e-3;
  /// Q_n, added once per step before propagation.
  Mat3 pose_regularisation = Vec3(1e-9, 1e-9, 1e-18).asDiagonal();
  /// Sequential (default) or keyed random draws (common random numbers, ci/GATES.md).
  DrawStreams draw_streams = DrawStreams::kSequential;

  /// Throws std::invalid_argument naming the field: particles >= 1; ess_threshold >= 0;
  /// ipl_iterations >= 1; ipl_kl_tolerance >= 0; pose_regularisation finite and symmetric.
  void Validate() const;
};

/// A landmark EKF of one particle. `seen` is false until the landmark's first measurement.
struct OracleLandmark {
  Landmark mean = Landmark::Zero();
  Mat2 cov = Mat2::Zero();
  bool seen = false;
};

/// A particle's map: one EKF slot per landmark index.
struct OracleMap {
  std::vector<OracleLandmark> landmarks;
};

/// The known-association map model of the skeleton.
class OracleMapModel {
 public:
  using Map = OracleMap;
  using Snapshot = std::vector<OracleLandmark>;

  /// `origins[k]` holds the hidden origin labels of step k (landmark index >= 0 or
  /// datasets::kClutter). Throws std::invalid_argument for a label below kClutter (e.g. Victoria
  /// Park's kUnknownOrigin: real detections have no known origin) or a landmark measured twice in
  /// one scan.
  OracleMapModel(std::vector<std::vector<int>> origins, const Mat2& measurement_noise);

  [[nodiscard]] Map InitialMap() const;
  /// Selects the step's origin labels (an internal counter). Throws std::invalid_argument when
  /// called more often than there are origin rows or when the measurement count differs from the
  /// label count.
  void BeginStep(const StepData& step);
  void BeforePrediction(Map& /*map*/, const Pose& /*pose*/) const {}
  /// The re-observed landmarks (seen before) in ascending landmark order, with the known
  /// association of every measurement into that list.
  [[nodiscard]] filters::MapView View(const Map& map);
  /// Also adds to `nis` the NIS of every re-observed landmark's measurement with the S of its
  /// likelihood term (Hm P Hm^T + R at the sampled pose).
  void Update(Map& map, const Pose& pose, const StepData& step, double& log_weight,
              filters::InnovationStats& nis) const;
  void Update(Map& map, const Pose& pose, const StepData& step, double& log_weight) const {
    filters::InnovationStats unused;
    Update(map, pose, step, log_weight, unused);
  }
  [[nodiscard]] Snapshot Estimate(const Map& map) const { return map.landmarks; }
  /// Every initialised landmark in landmark order, with log-weight 0.
  [[nodiscard]] filters::MapEstimate ToMapEstimate(const Snapshot& snapshot) const;
  [[nodiscard]] int ComponentCount(const Map& map) const;
  [[nodiscard]] int steps_done() const { return static_cast<int>(step_index_); }

 private:
  std::vector<std::vector<int>> origins_;
  Mat2 noise_cov_;
  int landmark_slots_ = 0;
  std::size_t step_index_ = 0;
  const std::vector<int>* origin_ = nullptr;  ///< labels of the current step
  std::vector<int> by_landmark_;              ///< its landmark measurements, by landmark index
  std::vector<phd::GaussianComponent> view_;
  std::vector<int> view_association_;
};

using OracleRbpf = filters::ParticleFilter<OracleMapModel>;

/// The oracle with explicit origin labels. Throws std::invalid_argument for invalid params,
/// a context without motion model, or invalid labels (OracleMapModel).
std::unique_ptr<OracleRbpf> MakeOracle(filters::EstimatorContext context,
                                       std::vector<std::vector<int>> origins,
                                       const OracleParams& params, std::uint64_t stream_seed);

/// The known-association map model with another importance density (e.g. the transition density:
/// FastSLAM 1.0 with known association); `params` as for the oracle.
std::unique_ptr<OracleRbpf> MakeKnownAssociationFilter(
    filters::EstimatorContext context, std::vector<std::vector<int>> origins,
    const OracleParams& params, std::unique_ptr<filters::ImportanceDensity> density,
    std::uint64_t stream_seed);

/// Origin labels of every step of a scenario, checked against its measurement counts. Throws
/// std::invalid_argument naming the scenario and step when a step's labels are missing.
std::vector<std::vector<int>> ScenarioOrigins(const datasets::Scenario& scenario);

/// The oracle of a scenario: its public context, origins from its steps. Throws
/// std::invalid_argument naming the scenario when a step with measurements has no origin labels
/// or a label is unknown.
std::unique_ptr<OracleRbpf> MakeOracle(const datasets::Scenario& scenario,
                                       const OracleParams& params, std::uint64_t stream_seed);

}  // namespace phdslam::oracle

extern template class phdslam::filters::ParticleFilter<phdslam::oracle::OracleMapModel>;
