#include "src/filters/rb_phd_slam.h"

#include <cmath>
#include <utility>

namespace phdslam::filters {

PhdMapModel::PhdMapModel(const EstimatorContext& context, const PhdSlamParams& params)
    : sensor_(context.sensor), map_params_(params.map), weighting_(params.weighting) {
  if (!std::isnan(params.estimate_log_weight_threshold)) {
    estimate_threshold_ = params.estimate_log_weight_threshold;
  } else {
    const double q = 1.0 - context.sensor.pd_nominal;
    estimate_threshold_ = std::log(q * q);
  }
}

void PhdMapModel::BeforePrediction(Map& map, const Pose& pose) const {
  // Births at the pose the measurements were taken from, appended after existing components.
  if (map.births.empty()) return;
  map.gm.AddBirths(pose, map.births, sensor_.noise_cov, map_params_);
  map.births.clear();
}

void PhdMapModel::Update(Map& map, const Pose& pose, const StepData& step, double& log_weight,
                         InnovationStats& nis) const {
  if (weighting_ == RbPhdWeighting::kPaper46) {
    const phd::PhdUpdateResult update =
        map.gm.Update(pose, step.measurements, sensor_, map_params_);
    log_weight += update.log_likelihood;
    nis.nis_sum += update.nis_sum;
    nis.count += update.nis_count;
    KeepBirthsAndReduce(map, pose, step, update.ungated);
    return;
  }
  const std::vector<phd::GaussianComponent> predicted = map.gm.active();
  const phd::PhdUpdateResult update = map.gm.Update(pose, step.measurements, sensor_, map_params_);
  nis.nis_sum += update.nis_sum;
  nis.count += update.nis_count;
  const std::vector<phd::GaussianComponent> passive = map.gm.passive();
  const PhdIntensityPair v{predicted, map.gm.active(), passive};
  log_weight +=
      RbPhdLogWeight(weighting_, update.log_likelihood, v, pose, step.measurements, sensor_);
  KeepBirthsAndReduce(map, pose, step, update.ungated);
}

void PhdMapModel::KeepBirthsAndReduce(Map& map, const Pose& pose, const StepData& step,
                                      const std::vector<int>& ungated) const {
  map.births.clear();
  for (int j : ungated) map.births.push_back(step.measurements[j]);
  // Hypothesis reduction and active/passive bookkeeping.
  map.gm.Reduce(pose, sensor_, map_params_);
}

MapEstimate PhdMapModel::ToMapEstimate(const Snapshot& snapshot) const {
  MapEstimate m;
  for (const auto& c : snapshot.Estimate(estimate_threshold_)) {
    m.means.push_back(c.mean);
    m.covs.push_back(c.cov);
    m.log_weights.push_back(c.log_weight);
  }
  return m;
}

ParticleFilterParams SkeletonParams(const PhdSlamParams& params) {
  ParticleFilterParams s;
  s.particles = params.particles;
  s.resampling = params.resampling;
  s.ess_threshold_kind = params.ess_threshold_kind;
  s.ess_threshold = params.ess_threshold;
  s.pose_regularisation = params.pose_regularisation;
  s.reuse_parent_proposal = params.reuse_parent_proposal;
  s.draw_streams = params.draw_streams;
  return s;
}

std::unique_ptr<RbPhdSlam> MakeRbPhdSlam(EstimatorContext context, const PhdSlamParams& params,
                                         std::unique_ptr<ImportanceDensity> density,
                                         std::uint64_t stream_seed) {
  PhdMapModel model(context, params);
  return std::make_unique<RbPhdSlam>(std::move(context), SkeletonParams(params), std::move(model),
                                     std::move(density), stream_seed);
}

}  // namespace phdslam::filters

template class phdslam::filters::ParticleFilter<phdslam::filters::PhdMapModel>;
