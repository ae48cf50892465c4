// The oracle RBPF: FastSLAM 2.0 with known data association and the partitioned IPL proposal
// (reference notes section 16, "Oracle RBPF"). It is the only estimator that reads the scenario's
// hidden origin labels, and it serves as the accuracy bound the PHD-SLAM filters are compared
// with.
//
// One recursion, with the step structure and random-number layout of RbPhdSlam:
//   1. draw N uniforms (unused; drawn so that the stream layout matches RbPhdSlam) and 3N
//      standard normals;
//   2. for each particle in index order:
//      a. predict the pose Gaussian (Q_n once, then every sub-interval; nothing at a step with a
//         single time stamp), exactly as RbPhdSlam::Predict;
//      b. proposal: the partitioned IPL (ipl.h) from the predicted Gaussian over the measurements
//         of landmarks this particle has seen before, in ascending landmark order;
//      c. sample x = mu + chol(Sigma) xi and add log N(x; mu0, Sigma0) - log q(x); when the
//         proposal covariance has no Cholesky factor the pose stays at the predicted mean and
//         this term is skipped; with no re-observed landmark q is the prior and the term is 0;
//      d. for each re-observed landmark add log N(z; h(m, x), Hm P Hm^T + R) (bearing residual
//         wrapped) and apply the EKF update at x; initialise first sightings with the inverse
//         model at x (covariance G R G^T);
//   3. the estimate is the highest-weight particle (first on ties), before resampling;
//   4. resample (stratified, notes 14) when N > 1, resampling is on and ESS <= ess_threshold N;
//      this draws N more uniforms.
// Clutter measurements are discarded and missed detections are simply absent, so neither touches
// the weights or the random stream: removing clutter from a scenario leaves the result unchanged.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "datasets/scenario.h"
#include "src/core/random.h"
#include "src/core/types.h"
#include "src/filters/estimator.h"

namespace phdslam::oracle {

struct OracleParams {
  int particles = 1;
  bool resampling = true;
  double ess_threshold = 0.2;  ///< resample when ESS <= ess_threshold * N
  int ipl_iterations = 5;      ///< L
  double ipl_kl_tolerance = 1e-3;
  /// Q_n, added once per step before propagation.
  Mat3 pose_regularisation = Vec3(1e-9, 1e-9, 1e-18).asDiagonal();

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

struct OracleParticle {
  Pose pose = Pose::Zero();
  Mat3 cov = Mat3::Zero();  ///< non-zero only between prediction and sampling
  double log_weight = 0.0;
  std::vector<OracleLandmark> landmarks;  ///< indexed by landmark id
};

class OracleRbpf final : public filters::OnlineEstimator {
 public:
  /// `origins[k]` holds the hidden origin labels of step k (landmark index >= 0 or
  /// datasets::kClutter). Throws std::invalid_argument for invalid params or a label below
  /// kClutter (e.g. Victoria Park's kUnknownOrigin: real detections have no known origin).
  OracleRbpf(filters::EstimatorContext context, std::vector<std::vector<int>> origins,
             OracleParams params, std::uint64_t stream_seed);

  /// The oracle of a scenario: context = EstimatorContext::FromScenario(scenario), origins from
  /// its steps. Throws std::invalid_argument naming the scenario when a step with measurements
  /// has no origin labels or a label is unknown.
  static std::unique_ptr<OracleRbpf> FromScenario(const datasets::Scenario& scenario,
                                                  OracleParams params, std::uint64_t stream_seed);

  /// Processes the next step (an internal counter selects its origin labels). Throws
  /// std::invalid_argument when called more often than there are origin rows or when the step's
  /// measurement count differs from its label count. StepOutput::association holds, for each
  /// measurement, the best particle's landmark mean before this step's update, NaN for clutter
  /// and first sightings.
  filters::StepOutput Step(const datasets::StepData& step) override;

  /// Every initialised landmark of the best particle of the last step, in landmark order, with
  /// log-weight 0. Empty before the first step.
  [[nodiscard]] filters::MapEstimate Map() const override;

  [[nodiscard]] const std::vector<OracleParticle>& particles() const { return particles_; }
  /// Index (before resampling) of the particle the last estimate came from.
  [[nodiscard]] int best_particle() const { return best_; }
  [[nodiscard]] int steps_done() const { return static_cast<int>(step_index_); }

 private:
  void Predict(OracleParticle& particle, const datasets::StepData& step) const;

  filters::EstimatorContext context_;
  std::vector<std::vector<int>> origins_;
  OracleParams params_;
  RandomStream rng_;
  std::vector<OracleParticle> particles_;
  std::size_t step_index_ = 0;
  int best_ = 0;
  std::vector<OracleLandmark> best_landmarks_;  ///< snapshot of the last estimate's map
};

}  // namespace phdslam::oracle
