// The joint prediction/update of a delta-GLMB map at one pose (docs/algorithms/glmb-slam.md section
// 4): the entry terms, the eta matrix of each prior hypothesis (out-of-FOV entries passed through
// with factor 1, never entering the sampler), Gibbs sampling from the optimal association,
// children, the normaliser, merging of duplicates, pruning and the cap. Every weight is a natural
// log.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "src/core/random.h"
#include "src/glmb/entry_terms.h"
#include "src/glmb/gibbs_sampler.h"
#include "src/glmb/glmb_density.h"

namespace phdslam::glmb {

/// A birth Bernoulli offered to the update: its entry and existence r_B.
struct BirthTrack {
  TrackPtr track;
  double existence = 0.0;
};

struct UpdateSettings {
  double survival_probability = 0.95;  ///< p_S inside the FOV (1 outside)
  double log_clutter_intensity = 0.0;  ///< log kappa(z), uniform over the measurement space
  double clutter_rate = 0.0;           ///< Lambda = <kappa, 1>
  int samples = 1000;                  ///< H_upd: Gibbs samples shared out over the parents
  double prune_threshold = 1e-5;       ///< hypotheses with w <= threshold are dropped
  int max_hypotheses = 1000;           ///< H_max
  /// Start each chain from the optimal association (true) or from [V]'s all-missed state.
  bool optimal_start = true;
};

/// The sampler's problem: the distinct entries with their terms and one eta matrix per parent.
struct JointProblem {
  struct Parent {
    double log_weight = 0.0;
    std::vector<int> rows;  ///< entry indices of the in-FOV entries, then the births
    int in_fov_rows = 0;    ///< rows[0, in_fov_rows) are prior entries, in id order
    std::shared_ptr<const TrackSet> tracks;  ///< the prior hypothesis' entries
  };
  /// Distinct in-FOV prior entries (first-seen order), then births; the prior's out-of-FOV
  /// entries are not here (they pass through from Parent::tracks).
  std::vector<TrackPtr> entries;
  std::vector<EntryTerms> terms;  ///< aligned with entries
  std::vector<EtaRow> eta;        ///< aligned with entries: each entry's eta row
  int prior_entries = 0;
  std::vector<Parent> parents;
  int measurements = 0;
  double log_ck = 0.0;  ///< c_k = -Lambda + sum_j log kappa(z_j)

  /// The eta matrix of parent h: the rows of its entries (parents[h].rows), shared, not copied.
  [[nodiscard]] EtaRows EtaOf(std::size_t h) const { return {eta, parents[h].rows}; }
};

/// Builds the problem at pose x. `existence`, when not empty, holds per entry of the single
/// prior hypothesis a multiplier of its survival probability (LMB-SLAM: its existence r,
/// docs/algorithms/glmb-slam.md section 7); otherwise survivors have existence p_S.
JointProblem BuildJointProblem(std::span<const Hypothesis> prior, std::span<const double> existence,
                               std::span<const BirthTrack> births, const Pose& x,
                               std::span<const Measurement> measurements,
                               const MeasurementSetup& setup, const UpdateSettings& settings);

/// One distinct sampled association of one parent with its unnormalised log-weight
/// log w_h + sum_i log eta_i(gamma_i) + c_k.
struct SampledAssociation {
  int parent = 0;
  std::span<const int> gamma;  ///< a view of the values it was sampled into (SampledAssociations)
  double log_weight = 0.0;
};

/// The sampled associations of a joint problem, their values one after the other in one buffer
/// that their views point into. Movable (the buffer moves with them), not copyable.
struct SampledAssociations {
  SampledAssociations() = default;
  SampledAssociations(SampledAssociations&&) = default;
  SampledAssociations& operator=(SampledAssociations&&) = default;
  SampledAssociations(const SampledAssociations&) = delete;
  SampledAssociations& operator=(const SampledAssociations&) = delete;
  ~SampledAssociations() = default;

  std::vector<int> values;
  std::vector<SampledAssociation> samples;
};

/// T_h = round(H_upd sqrt(w_h) / sum sqrt(w_h')), at least 1, samples per parent; distinct
/// samples in parent order. A parent without a valid association contributes nothing.
SampledAssociations SampleAssociations(const JointProblem& problem, const UpdateSettings& settings,
                                       RandomStream& rng);

struct UpdateResult {
  std::vector<Hypothesis> hypotheses;  ///< normalised, pruned and capped, descending weight
  double log_normaliser = 0.0;         ///< log Z-hat over all children, before normalisation
  /// r_U(z_j): the posterior weight of the hypotheses that assign z_j.
  std::vector<double> measurement_assigned;
  /// Whether z_j gates with an in-FOV entry of the highest-weight prior hypothesis.
  std::vector<char> measurement_gates_best_prior;
  /// Innovations (nu, S) of the detections of the highest-weight posterior hypothesis.
  std::vector<std::pair<Vec2, Mat2>> best_innovations;
};

/// Children of the samples at pose x: pass-through entries, missed entries kept by id, detected
/// entries replaced by their EKF child (created once per (entry, measurement), ids from
/// `next_id`), dead ones dropped; merged by entry-id set, normalised, pruned, capped.
UpdateResult BuildPosterior(const JointProblem& problem,
                            std::span<const SampledAssociation> samples, const Pose& x,
                            std::span<const Measurement> measurements,
                            const MeasurementSetup& setup, const UpdateSettings& settings,
                            std::uint64_t& next_id);

/// BuildJointProblem, SampleAssociations and BuildPosterior at a sampled pose (no pose term).
/// When no parent has a valid association the prior is returned with log_normaliser = -inf.
UpdateResult JointUpdate(std::span<const Hypothesis> prior, std::span<const double> existence,
                         std::span<const BirthTrack> births, const Pose& x,
                         std::span<const Measurement> measurements, const MeasurementSetup& setup,
                         const UpdateSettings& settings, RandomStream& rng, std::uint64_t& next_id);

}  // namespace phdslam::glmb
