// The one Rao-Blackwellised particle-filter skeleton of the suite. A filter is its map model (the
// per-particle map type with its prediction, update and estimate), its importance density and its
// parameters; PHD-SLAM 1.0/2.0a/2.0b/3.0 (GM-PHD maps, phd_map_model.h) and the oracle RBPF
// (known-association landmark EKFs, oracle/) are instances.
//
// One recursion (docs/algorithms/phd-slam.md section 2.2, section 4.1, section 6):
//   1. draw N uniforms (component choice) and 3N standard normals (pose draw), in that order;
//   2. for each particle in index order:
//      a. Model::BeforePrediction (e.g. births from the previous scan), then the pose Gaussian is
//         predicted over the step (pose_prediction.h);
//      b. the importance density is built from the predicted Gaussian, the map's landmark view
//         and the scan; consecutive copies of one resampled parent share it when
//         reuse_parent_proposal is set (they have equal predictions, so results do not change);
//         (a model with its own Propose, ProposesFromMap, builds it from the whole map instead);
//      c. a component t is picked with the particle's uniform and x = mu_t + chol(Sigma_t) xi is
//         drawn; unless the proposal is the prior itself, log N(x; mu0, Sigma0) - log q(x) is added
//         to the log-weight (or the proposal's own log_weight_increment when it sets one); without
//         a Cholesky factor the pose stays at the predicted mean;
//      d. Model::Update adds the measurement likelihood to the log-weight and updates the map at x;
//   3. the estimate is the highest-weight particle (first on ties), before resampling; its map is
//      kept as a snapshot (Model::Snapshot);
//   4. ESS of the normalised weights, the weighted particle spread about the estimate as pose
//      covariance, and stratified resampling (N more uniforms) when N > 1, resampling is on and
//      ESS <= threshold (relative: threshold N; absolute: threshold).
// Consistency outputs (no random numbers, no effect on poses or weights):
//   - the Rao-Blackwellised pose posterior (StepOutput::pose_mean_rb / pose_cov_rb): in 2b/2c
//     each particle's proposal is moment-matched (pose_mixture_moments.h; its components with
//     their normalised weights) and, after the loop, these Gaussians are moment-matched across
//     particles with the log-weights carried into the step (after the previous resampling,
//     before this step's log f - log q and likelihood terms). Those are the weights under which
//     the particles are a sample of the previous posterior, so the mixture is the distribution
//     this step draws the poses from. It is the pose posterior as far as the proposal is the
//     optimal importance density: for PHD-SLAM 3.0 and the oracle the IPL mixture, for 2.0a/2.0b
//     their EKF/IPL conditional, for PHD-SLAM 1.0 (the prior as proposal) the predicted Gaussian;
//   - NIS of the estimate's particle (StepDiagnostics::nis_sum / nis_count) when Model::Update
//     takes a filters::InnovationStats& as fifth argument.
// Every random number comes from the one stream seeded by the constructor, or, when draws are
// replayed (ReplayDraws, src/core/draw_replay.h), from a recording tagged by step, particle and
// purpose. A StepObserver (SetObserver) sees each particle's prediction, proposal and sample, its
// state after the update and the resampling sources, for step-by-step comparisons.
#pragma once

#include <cmath>
#include <concepts>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "src/core/draw_replay.h"
#include "src/core/gaussian.h"
#include "src/core/keyed_stream.h"
#include "src/core/random.h"
#include "src/core/step_data.h"
#include "src/filters/estimator.h"
#include "src/filters/importance_density.h"
#include "src/filters/innovation_stats.h"
#include "src/filters/particle_estimate.h"
#include "src/filters/particle_filter_params.h"
#include "src/filters/pose_mixture_moments.h"
#include "src/filters/pose_prediction.h"
#include "src/filters/resampling.h"

namespace phdslam::filters {

/// One particle: a pose sample, its log-weight and its map.
template <class Map>
struct Particle {
  Pose pose = Pose::Zero();
  Mat3 cov = Mat3::Zero();  ///< non-zero only between prediction and sampling
  double log_weight = 0.0;
  int parent = 0;       ///< source index after resampling; -1: compute own proposal
  InnovationStats nis;  ///< of this step's update (when the model reports it)
  Map map;
};

/// A map model whose Update also reports the NIS of the measurements it associated.
template <class Model>
concept ReportsInnovations = requires(const Model& m, typename Model::Map& map, const Pose& x,
                                      const StepData& step, double& w, InnovationStats& nis) {
  m.Update(map, x, step, w, nis);
};

/// Sees the inside of every step (ParticleFilter::SetObserver); no effect on the filter.
template <class ParticleType>
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  /// After particle `idx` is sampled, before its update: the predicted Gaussian (mu0, sigma0),
  /// the proposal it sampled from (normalised weights) and the particle with its new pose and
  /// log-weight.
  virtual void Sampled(int step, int idx, const Pose& mu0, const Mat3& sigma0,
                       const PreparedProposal& proposal, const ParticleType& p) = 0;
  /// After every particle's update and map reduction, before resampling.
  virtual void Updated(int step, int idx, const ParticleType& p) = 0;
  /// When the step resampled: the source index of each new particle.
  virtual void Resampled(int step, const std::vector<int>& sources) = 0;
};

/// What the importance density reads of a particle's map at one step.
struct MapView {
  LandmarkView landmarks;
  std::span<const int> known_association;  ///< empty unless the model knows the association
};

/// A map model that may build the pose proposal itself from the whole map (not only its landmark
/// view), returning nullopt to leave it to the importance density.
template <class Model>
concept ProposesFromMap = requires(const Model& m, const typename Model::Map& map,
                                   const ProposalInput& input) {
  { m.Propose(map, input) } -> std::same_as<std::optional<ProposalOutput>>;
};

/// A map model whose Update takes the map, the sampled pose, the scan and the log-weight to add
/// the measurement likelihood to (with or without the InnovationStats of ReportsInnovations).
template <class Model>
concept UpdatesMaps = ReportsInnovations<Model> ||
    requires(const Model& m, typename Model::Map& map, const Pose& x, const StepData& step,
             double& w) {
  m.Update(map, x, step, w);
};

/// What the skeleton requires of a map model (the per-particle map with its prediction, update
/// and estimate):
///   Map: the per-particle map, copied when particles are resampled; a copy is a value of its
///     own (updating the original leaves it unchanged, even where copies share storage);
///   Snapshot: the estimate's map kept between steps, default-constructible and copyable;
///   Map InitialMap() const;
///   void BeginStep(const StepData&);                      // per-step checks and bookkeeping
///   void BeforePrediction(Map&, const Pose& pose) const;  // at the pose before prediction
///   MapView View(const Map&);                             // valid until the next View call
///   void Update(Map&, const Pose&, const StepData&, double& log_weight) const;  // UpdatesMaps
///   Snapshot Estimate(const Map&) const;                  // the map estimate of the best particle
///   MapEstimate ToMapEstimate(const Snapshot&) const;
///   int ComponentCount(const Map&) const;                 // for the step diagnostics
/// The typed contract suite oracle/map_model_contract_test.cc checks the behaviour
/// behind these signatures for every map model.
template <class Model>
concept MapModel = std::move_constructible<Model> && std::copyable<typename Model::Map> &&
    std::copyable<typename Model::Snapshot> &&
    std::default_initializable<typename Model::Snapshot> && UpdatesMaps<Model> &&
    requires(Model& model, const Model& const_model, typename Model::Map& map,
             const typename Model::Map& const_map, const typename Model::Snapshot& snapshot,
             const Pose& x, const StepData& step) {
  { const_model.InitialMap() } -> std::same_as<typename Model::Map>;
  model.BeginStep(step);
  const_model.BeforePrediction(map, x);
  { model.View(const_map) } -> std::same_as<MapView>;
  { const_model.Estimate(const_map) } -> std::same_as<typename Model::Snapshot>;
  { const_model.ToMapEstimate(snapshot) } -> std::same_as<MapEstimate>;
  { const_model.ComponentCount(const_map) } -> std::same_as<int>;
};

/// The skeleton over a map model (MapModel).
template <MapModel Model>
class ParticleFilter final : public OnlineEstimator {
 public:
  using MapType = typename Model::Map;
  using ParticleType = Particle<MapType>;

  ParticleFilter(EstimatorContext context, ParticleFilterParams params, Model model,
                 std::unique_ptr<ImportanceDensity> density, std::uint64_t stream_seed)
      : context_(std::move(context)),
        params_(std::move(params)),
        model_(std::move(model)),
        density_(std::move(density)),
        stream_seed_(stream_seed),
        rng_(stream_seed) {
    const int n = std::max(1, params_.particles);
    particles_.resize(n);
    for (ParticleType& p : particles_) {
      p.pose = context_.initial_pose;
      p.log_weight = -std::log(static_cast<double>(n));
      p.parent = 0;  // every particle starts as a copy of one parent
      p.map = model_.InitialMap();
    }
  }

  StepOutput Step(const StepData& step) override;
  [[nodiscard]] MapEstimate Map() const override { return model_.ToMapEstimate(snapshot_); }
  [[nodiscard]] std::vector<std::pair<Pose, double>> ParticleStates() const override {
    std::vector<std::pair<Pose, double>> states;
    states.reserve(particles_.size());
    for (const ParticleType& p : particles_) states.emplace_back(p.pose, p.log_weight);
    return states;
  }

  [[nodiscard]] const std::vector<ParticleType>& particles() const { return particles_; }
  /// Gives every particle a copy of `map` (benchmarks and tests that start from a known map).
  void ResetMaps(const MapType& map) {
    for (ParticleType& p : particles_) p.map = map;
  }
  /// Index (before resampling) of the particle the last estimate came from.
  [[nodiscard]] int best_particle() const { return best_; }
  /// The top-ranked association of the last step's best particle (measurement -> landmark-view
  /// index before the update, -1 for none), when the importance density provides one.
  [[nodiscard]] const std::vector<int>& best_association() const { return best_association_; }
  [[nodiscard]] const Model& model() const { return model_; }

  /// Takes every random number from `replay` instead of the seeded stream (nullptr: back to the
  /// stream). Step k (counted from 0 since construction) asks for, per particle i, the uniform
  /// (k, i, component, 0) and the normals (k, i, pose, 0..2), then when resampling the uniforms
  /// (k, j, resample, 0).
  void ReplayDraws(std::shared_ptr<DrawReplay> replay) { replay_ = std::move(replay); }
  /// Reports each step's inside to `observer` (not owned; nullptr: none).
  void SetObserver(StepObserver<ParticleType>* observer) { observer_ = observer; }

 private:
  double DrawUniform(int particle, DrawPurpose purpose) {
    if (replay_) return replay_->Next(step_index_, particle, purpose, 0);
    if (params_.draw_streams == DrawStreams::kKeyed) {
      return DrawKeyStream(stream_seed_, step_index_, particle, purpose).Uniform();
    }
    return rng_.Uniform();
  }
  Vec3 DrawNormals(int particle) {
    Vec3 xi;
    if (!replay_ && params_.draw_streams == DrawStreams::kKeyed) {
      KeyedStream keyed = DrawKeyStream(stream_seed_, step_index_, particle, DrawPurpose::kPose);
      xi << keyed.Normal(), keyed.Normal(), keyed.Normal();
      return xi;
    }
    if (!replay_) {
      xi << rng_.Normal(), rng_.Normal(), rng_.Normal();
      return xi;
    }
    for (int d = 0; d < 3; ++d) xi[d] = replay_->Next(step_index_, particle, DrawPurpose::kPose, d);
    return xi;
  }

  /// Steps 2a-2d for one particle; returns the size of the proposal it used.
  void Propagate(int idx, const StepData& step, double uniform, const Vec3& normal);
  void Resample(const std::vector<double>& weights);

  EstimatorContext context_;
  ParticleFilterParams params_;
  Model model_;
  std::unique_ptr<ImportanceDensity> density_;
  std::uint64_t stream_seed_;
  RandomStream rng_;
  std::shared_ptr<DrawReplay> replay_;
  StepObserver<ParticleType>* observer_ = nullptr;
  int step_index_ = 0;
  std::vector<ParticleType> particles_;
  int best_ = 0;
  std::vector<int> best_association_;
  typename Model::Snapshot snapshot_{};

  // Per-step state shared between particles (proposal reuse and association bookkeeping).
  PreparedProposal proposal_;
  std::optional<double> proposal_increment_;  ///< ProposalOutput::log_weight_increment of proposal_
  int proposal_parent_ = -2;
  long hypotheses_total_ = 0;
  std::vector<int> association_owner_;
  std::vector<std::vector<int>> associations_;
  std::vector<std::vector<Landmark>> associated_means_;
  PoseMoments proposal_moments_;         ///< moments of proposal_
  std::vector<PoseMoments> rb_moments_;  ///< per particle: proposal moments, carried-in weight
};

template <MapModel Model>
void ParticleFilter<Model>::Propagate(int idx, const StepData& step, double uniform,
                                      const Vec3& normal) {
  ParticleType& p = particles_[idx];
  // 2a. Predict.
  model_.BeforePrediction(p.map, p.pose);
  PredictPoseGaussian(context_, step, params_.pose_regularisation, p.pose, p.cov);
  const Pose mu0 = p.pose;
  const Mat3 sigma0 = p.cov;
  // 2b. Proposal, shared by consecutive copies of one parent.
  const bool reuse = params_.reuse_parent_proposal && p.parent >= 0 && p.parent == proposal_parent_;
  if (!reuse) {
    const MapView view = model_.View(p.map);
    const ProposalInput input{
        mu0, sigma0, view.landmarks, step.measurements, &context_.sensor, view.known_association};
    ProposalOutput built;
    if constexpr (ProposesFromMap<Model>) {
      std::optional<ProposalOutput> own = model_.Propose(p.map, input);
      built = own ? std::move(*own) : density_->Build(input);
    } else {
      built = density_->Build(input);
    }
    proposal_increment_ = built.log_weight_increment;
    PrepareProposal(std::move(built.mixture), proposal_);
    std::vector<Landmark> means;
    if (!built.best_association.empty()) {
      means.assign(built.best_association.size(), Landmark::Constant(std::nan("")));
      for (std::size_t j = 0; j < means.size(); ++j) {
        const int c = built.best_association[j];
        if (c >= 0) means[j] = view.landmarks[c].mean;
      }
    }
    associated_means_.push_back(std::move(means));
    associations_.push_back(std::move(built.best_association));
    proposal_parent_ = p.parent;
    proposal_moments_ = ProposalMoments(proposal_, mu0);
  }
  rb_moments_[idx] = proposal_moments_;
  rb_moments_[idx].log_weight = p.log_weight;
  association_owner_[idx] = static_cast<int>(associations_.size()) - 1;
  hypotheses_total_ += static_cast<long>(proposal_.mixture.size());
  // 2c. Sample and add log f - log q.
  const int t = PickComponent(proposal_, uniform);
  if (proposal_.chol[t]) {
    const Pose x = proposal_.mixture.means[t] + *proposal_.chol[t] * normal;
    // log f - log q, exactly 0 when the proposal is the prior itself (the bootstrap case).
    const bool is_prior = proposal_.mixture.size() == 1 && proposal_.mixture.means[0] == mu0 &&
                          proposal_.mixture.covs[0] == sigma0;
    if (!is_prior && !proposal_increment_) {
      const auto log_prior = LogNormalPdf<3>(x, mu0, sigma0);
      if (log_prior) p.log_weight += *log_prior - density_->LogDensity(proposal_, x);
    }
    p.pose = x;
  } else {
    p.pose = mu0;
  }
  if (proposal_increment_) p.log_weight += *proposal_increment_;
  p.cov.setZero();
  p.parent = -1;
  if (observer_) observer_->Sampled(step_index_, idx, mu0, sigma0, proposal_, p);
  // 2d. Measurement likelihood and map update at the sampled pose.
  if constexpr (ReportsInnovations<Model>) {
    p.nis = InnovationStats{};
    model_.Update(p.map, p.pose, step, p.log_weight, p.nis);
  } else {
    model_.Update(p.map, p.pose, step, p.log_weight);
  }
}

template <MapModel Model>
StepOutput ParticleFilter<Model>::Step(const StepData& step) {
  model_.BeginStep(step);
  const int n = static_cast<int>(particles_.size());
  // 1. The step's random numbers: one uniform and three standard normals per particle.
  std::vector<double> uniforms(n);
  std::vector<Vec3> normals(n);
  for (int i = 0; i < n; ++i) uniforms[i] = DrawUniform(i, DrawPurpose::kComponent);
  for (int i = 0; i < n; ++i) normals[i] = DrawNormals(i);

  proposal_parent_ = -2;
  hypotheses_total_ = 0;
  association_owner_.assign(n, -1);
  associations_.clear();
  associated_means_.clear();
  rb_moments_.resize(n);
  // 2. Predict, sample, weight and update every particle.
  for (int idx = 0; idx < n; ++idx) Propagate(idx, step, uniforms[idx], normals[idx]);
  if (observer_) {
    for (int idx = 0; idx < n; ++idx) observer_->Updated(step_index_, idx, particles_[idx]);
  }

  // 3. Estimate from the highest-weight particle (first on ties), before resampling.
  best_ = static_cast<int>(
      HighestWeightIndex(particles_, [](const ParticleType& p) { return p.log_weight; }));
  best_association_ =
      associations_.empty() ? std::vector<int>{} : associations_[association_owner_[best_]];
  snapshot_ = model_.Estimate(particles_[best_].map);
  StepOutput out;
  out.pose = particles_[best_].pose;
  if (!associated_means_.empty()) {
    out.association = std::move(associated_means_[association_owner_[best_]]);
  }
  out.diag.map_components = model_.ComponentCount(particles_[best_].map);
  out.diag.hypotheses = static_cast<int>(std::lround(static_cast<double>(hypotheses_total_) / n));
  out.diag.nis_sum = particles_[best_].nis.nis_sum;
  out.diag.nis_count = particles_[best_].nis.count;
  if (const std::optional<PoseMoments> rb = MatchMoments(rb_moments_)) {
    out.pose_mean_rb = rb->mean;
    out.pose_cov_rb = rb->cov;
  }

  // 4. ESS and resampling.
  std::vector<double> log_w(n);
  for (int i = 0; i < n; ++i) log_w[i] = particles_[i].log_weight;
  const std::vector<double> w = NormalisedWeights(log_w);
  if (n > 1) {
    out.pose_cov = WeightedSpread(particles_, w, out.pose,
                                  [](const ParticleType& p) -> const Pose& { return p.pose; });
  }
  out.diag.ess = n == 1 ? 1.0 : EffectiveSampleSize(w);
  const double threshold = params_.ess_threshold_kind == EssThresholdKind::kRelative
                               ? params_.ess_threshold * n
                               : params_.ess_threshold;
  if (n > 1 && params_.resampling && out.diag.ess <= threshold) {
    Resample(w);
    out.diag.resampled = true;
  }
  ++step_index_;
  return out;
}

template <MapModel Model>
void ParticleFilter<Model>::Resample(const std::vector<double>& weights) {
  const int n = static_cast<int>(particles_.size());
  std::vector<double> r(n);
  for (int j = 0; j < n; ++j) r[j] = DrawUniform(j, DrawPurpose::kResample);
  const std::vector<int> sources = StratifiedResample(weights, r);
  if (observer_) observer_->Resampled(step_index_, sources);
  // A source's last copy takes its particle by move (its map's storage is not copied again).
  std::vector<int> last_use(n, -1);
  for (int j = 0; j < n; ++j) last_use[sources[j]] = j;
  std::vector<ParticleType> next;
  next.reserve(n);
  const double log_uniform = -std::log(static_cast<double>(n));
  for (int j = 0; j < n; ++j) {
    const int s = sources[j];
    if (last_use[s] == j) {
      next.push_back(std::move(particles_[s]));
    } else {
      next.push_back(particles_[s]);
    }
    next.back().log_weight = log_uniform;
    next.back().parent = s;
  }
  particles_ = std::move(next);
}

}  // namespace phdslam::filters
