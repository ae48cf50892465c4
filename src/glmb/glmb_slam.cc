#include "src/glmb/glmb_slam.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include "src/core/log_sum_exp.h"
#include "src/glmb/kernel_proposal.h"

namespace phdslam::glmb {

namespace {

/// log kappa: the sensor's clutter intensity, in the space `space` when one is given.
double LogClutterIntensity(models::SensorModel sensor, std::optional<models::ClutterSpace> space) {
  if (space) sensor.clutter_space = *space;
  return std::log(sensor.ClutterIntensity());
}

void AddInnovations(const UpdateResult& result, filters::InnovationStats& nis) {
  for (const auto& [nu, s] : result.best_innovations) nis.Add(nu, s);
}

filters::MapEstimate EstimateOf(const std::vector<TrackPtr>& tracks,
                                const std::vector<double>& existence) {
  filters::MapEstimate m;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const TrackComponent& c = tracks[i]->Heaviest();
    m.means.push_back(c.mean);
    m.covs.push_back(c.cov);
    m.log_weights.push_back(std::log(existence[i]));
  }
  return m;
}

}  // namespace

LabelledMapCommon::LabelledMapCommon(const filters::EstimatorContext& context,
                                     const GlmbSlamParams& params, std::uint64_t stream_seed)
    : params_(params),
      sensor_(std::make_shared<const models::SensorModel>(context.sensor)),
      rng_(std::make_unique<RandomStream>(DeriveSeed(stream_seed, HashName("glmb-gibbs")))) {
  settings_.survival_probability = params.survival_probability;
  settings_.log_clutter_intensity = LogClutterIntensity(*sensor_, params.clutter_space);
  settings_.clutter_rate =
      std::max(sensor_->clutter_rate, models::SensorModel::kMinFilterClutterRate);
  settings_.samples = params.gibbs_samples;
  settings_.prune_threshold = params.hypothesis_prune_threshold;
  settings_.max_hypotheses = params.max_hypotheses;
  settings_.optimal_start = params.optimal_start;
  setup_.sensor = sensor_.get();
  setup_.noise_cov = sensor_->noise_cov;
  setup_.gate = -2.0 * std::log1p(-params.gate_probability);
}

// ---------------------------------------------------------------------------------------------
// delta-GLMB

GlmbMapModel::GlmbMapModel(const filters::EstimatorContext& context, const GlmbSlamParams& params,
                           bool optimal_kernel, std::uint64_t stream_seed)
    : common_(context, params, stream_seed), optimal_kernel_(optimal_kernel) {}

filters::MapView GlmbMapModel::View(const Map& map) {
  view_.clear();
  const int best = BestHypothesis(map.hypotheses);
  if (best >= 0) {
    for (const TrackPtr& t : *map.hypotheses[best].tracks) {
      const TrackComponent& c = t->Heaviest();
      view_.push_back(phd::GaussianComponent{c.mean, c.cov, 0.0});
    }
  }
  return {view_, {}};
}

std::optional<filters::ProposalOutput> GlmbMapModel::Propose(
    const Map& map, const filters::ProposalInput& input) const {
  if (!optimal_kernel_) return std::nullopt;
  const GlmbSlamParams& params = common_.params();
  MeasurementSetup setup = common_.setup();
  setup.pose_cov = input.predicted_cov;
  const JointProblem problem =
      BuildJointProblem(map.hypotheses, {}, map.births, input.predicted_mean, input.measurements,
                        setup, common_.settings());
  const SampledAssociations sampled =
      SampleAssociations(problem, common_.settings(), common_.rng());
  KernelProposal kernel = BuildKernelProposal(
      problem, sampled.samples, input.predicted_mean, input.predicted_cov, input.measurements,
      setup.noise_cov, params.kernel_associations, params.kernel_form);
  filters::ProposalOutput out;
  out.mixture = std::move(kernel.mixture);
  if (params.kernel_weight == KernelWeight::kMarginal)
    out.log_weight_increment = kernel.log_marginal;
  if (params.kernel_weight == KernelWeight::kNormaliser) out.log_weight_increment = 0.0;
  return out;
}

void GlmbMapModel::Update(Map& map, const Pose& pose, const StepData& step, double& log_weight,
                          filters::InnovationStats& nis) const {
  UpdateResult result =
      JointUpdate(map.hypotheses, {}, map.births, pose, step.measurements, common_.setup(),
                  common_.settings(), common_.rng(), map.next_id);
  const bool marginal_weight =
      optimal_kernel_ && common_.params().kernel_weight == KernelWeight::kMarginal;
  if (!marginal_weight) log_weight += result.log_normaliser;
  AddInnovations(result, nis);
  map.hypotheses = std::move(result.hypotheses);
  ++map.updates;
  map.births = MakeBirths(pose, step.measurements, common_.setup().noise_cov, result,
                          common_.params().birth, map.updates + 1, map.next_id);
}

GlmbMapModel::Snapshot GlmbMapModel::Estimate(const Map& map) const {
  const int h = MapCardinalityHypothesis(map.hypotheses);
  if (h < 0) return {};
  const std::vector<std::pair<Label, double>> r = LabelExistence(map.hypotheses);
  const std::map<Label, double> existence(r.begin(), r.end());
  const TrackSet& tracks = *map.hypotheses[h].tracks;
  std::vector<double> r_of;
  r_of.reserve(tracks.size());
  for (const TrackPtr& t : tracks) r_of.push_back(existence.at(t->label));
  return EstimateOf(tracks, r_of);
}

// ---------------------------------------------------------------------------------------------
// LMB

LmbMapModel::LmbMapModel(const filters::EstimatorContext& context, const GlmbSlamParams& params,
                         std::uint64_t stream_seed)
    : common_(context, params, stream_seed) {}

filters::MapView LmbMapModel::View(const Map& map) {
  view_.clear();
  for (const Bernoulli& b : map.tracks) {
    const TrackComponent& c = b.track->Heaviest();
    view_.push_back(phd::GaussianComponent{c.mean, c.cov, std::log(b.existence)});
  }
  return {view_, {}};
}

namespace {

/// Prune by existence, reduce each mixture (a new entry when it changes), cap by existence.
std::vector<Bernoulli> PruneAndReduce(std::vector<Bernoulli> tracks, const GlmbSlamParams& params,
                                      std::uint64_t& next_id) {
  std::vector<Bernoulli> kept;
  for (Bernoulli& b : tracks) {
    if (b.existence < params.existence_prune_threshold) continue;
    if (b.track->gm.size() > 1) {
      Track reduced{next_id++, b.track->label, ReduceMixture(b.track->gm, params.mixture)};
      b.track = std::make_shared<const Track>(std::move(reduced));
    }
    kept.push_back(std::move(b));
  }
  if (static_cast<int>(kept.size()) > params.max_tracks) {
    std::stable_sort(kept.begin(), kept.end(), [](const Bernoulli& a, const Bernoulli& b) {
      return a.existence > b.existence;
    });
    kept.resize(params.max_tracks);
  }
  return kept;
}

}  // namespace

void LmbMapModel::Update(Map& map, const Pose& pose, const StepData& step, double& log_weight,
                         filters::InnovationStats& nis) const {
  const models::SensorModel& sensor = *common_.setup().sensor;
  std::vector<Bernoulli> outside;
  std::vector<Bernoulli> inside;
  for (Bernoulli& b : map.tracks) {
    const bool in = sensor.DetectionProbability(pose, b.track->Heaviest().mean) > 0.0;
    (in ? inside : outside).push_back(std::move(b));
  }
  std::sort(inside.begin(), inside.end(),
            [](const Bernoulli& a, const Bernoulli& b) { return a.track->id < b.track->id; });
  auto set = std::make_shared<TrackSet>();
  std::vector<double> existence;
  for (const Bernoulli& b : inside) {
    set->push_back(b.track);
    existence.push_back(b.existence);
  }
  const std::vector<Hypothesis> prior{Hypothesis{std::move(set), 0.0}};
  const UpdateResult result =
      JointUpdate(prior, existence, map.births, pose, step.measurements, common_.setup(),
                  common_.settings(), common_.rng(), map.next_id);
  log_weight += result.log_normaliser;
  AddInnovations(result, nis);
  std::vector<Bernoulli> updated = result.log_normaliser == kNegInf
                                       ? std::move(inside)
                                       : GlmbToLmb(result.hypotheses, map.next_id);
  updated = PruneAndReduce(std::move(updated), common_.params(), map.next_id);
  for (Bernoulli& b : outside) updated.push_back(std::move(b));
  std::sort(updated.begin(), updated.end(),
            [](const Bernoulli& a, const Bernoulli& b) { return a.track->label < b.track->label; });
  map.tracks = std::move(updated);
  ++map.updates;
  map.births = MakeBirths(pose, step.measurements, common_.setup().noise_cov, result,
                          common_.params().birth, map.updates + 1, map.next_id);
}

LmbMapModel::Snapshot LmbMapModel::Estimate(const Map& map) const {
  std::vector<TrackPtr> tracks;
  std::vector<double> r;
  for (int i : LmbEstimateIndices(map.tracks)) {
    tracks.push_back(map.tracks[i].track);
    r.push_back(map.tracks[i].existence);
  }
  return EstimateOf(tracks, r);
}

// ---------------------------------------------------------------------------------------------

std::unique_ptr<GlmbSlam> MakeGlmbSlam(filters::EstimatorContext context,
                                       const GlmbSlamParams& params, bool optimal_kernel,
                                       std::uint64_t stream_seed) {
  GlmbMapModel model(context, params, optimal_kernel, stream_seed);
  return std::make_unique<GlmbSlam>(std::move(context), SkeletonParams(params), std::move(model),
                                    std::make_unique<filters::TransitionDensity>(), stream_seed);
}

std::unique_ptr<LmbSlam> MakeLmbSlam(filters::EstimatorContext context,
                                     const GlmbSlamParams& params, std::uint64_t stream_seed) {
  LmbMapModel model(context, params, stream_seed);
  return std::make_unique<LmbSlam>(std::move(context), SkeletonParams(params), std::move(model),
                                   std::make_unique<filters::TransitionDensity>(), stream_seed);
}

}  // namespace phdslam::glmb

template class phdslam::filters::ParticleFilter<phdslam::glmb::GlmbMapModel>;
template class phdslam::filters::ParticleFilter<phdslam::glmb::LmbMapModel>;
