#include "validation/runner/parent_weights.h"

#include <cmath>
#include <stdexcept>

#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/core/random.h"
#include "src/filters/estimator.h"
#include "src/filters/pose_prediction.h"
#include "src/filters/sc_phd_slam.h"
#include "validation/runner/results_io.h"

namespace phdslam::validation {
namespace {

double EffectiveSampleSize(const std::vector<double>& w) {
  double sum_sq = 0.0;
  for (double v : w) sum_sq += v * v;
  return sum_sq > 0.0 ? 1.0 / sum_sq : 0.0;
}

nlohmann::json PoseJson(const Pose& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

ParentWeights CompareParentWeightingAtStep(const datasets::Scenario& scenario,
                                           const ParentWeightsSettings& settings) {
  const std::size_t k = settings.step;
  if (k == 0 || k >= scenario.steps.size()) {
    throw std::invalid_argument("parent weights: step must be in 1.." +
                                std::to_string(scenario.steps.size() - 1) + ", got " +
                                std::to_string(k));
  }
  if (settings.parents > kMaxParents) {
    throw std::invalid_argument("parent weights: parents must be at most " +
                                std::to_string(kMaxParents) + ", got " +
                                std::to_string(settings.parents));
  }
  if (settings.parents < 2) {
    throw std::invalid_argument("parent weights: parents must be >= 2, got " +
                                std::to_string(settings.parents));
  }
  if (!(settings.spread > 0.0) || !std::isfinite(settings.spread)) {
    throw std::invalid_argument("parent weights: spread must be positive and finite, got " +
                                std::to_string(settings.spread));
  }
  const datasets::StepData& scan = scenario.steps[k].data;
  if (scan.measurements.empty()) {
    throw std::invalid_argument("parent weights: step " + std::to_string(k) +
                                " has no measurements; choose another --step");
  }
  const filters::EstimatorContext context = filters::EstimatorContext::FromScenario(scenario);
  filters::ScPhdSlamParams params = filters::ScPhdSlamParams::ForScenario(scenario.name);
  params.particles = 1;
  filters::ScPhdSlam filter(context, params, DeriveSeed(settings.stream_seed, 1));
  for (std::size_t j = 0; j < k; ++j) filter.Step(scenario.steps[j].data);
  const filters::ScParent& parent = filter.parents()[filter.best_parent()];

  ParentWeights w;
  w.step = k;
  w.previous_pose = parent.pose;
  w.predicted_mean = parent.pose;
  filters::PredictPoseGaussian(context, scan, params.pose_regularisation, w.predicted_mean,
                               w.predicted_cov);
  if (scenario.truth.poses.size() == scenario.steps.size()) w.true_pose = scenario.truth.poses[k];
  w.measurements = scan.measurements.size();
  w.map_components = parent.map.size();

  RandomStream rng(DeriveSeed(settings.stream_seed, 2));
  w.spread = settings.spread;
  // The predicted covariance is nearly singular in the heading (Q_n's 1e-18), where a Cholesky
  // may fail: an eigen-decomposition square root has no such case.
  const Mat3 root = settings.spread * PsdSquareRoot<3>(w.predicted_cov);
  w.poses.reserve(static_cast<std::size_t>(settings.parents));
  for (int i = 0; i < settings.parents; ++i) {
    const Vec3 xi(rng.Normal(), rng.Normal(), rng.Normal());
    w.poses.push_back(w.predicted_mean + root * xi);
  }
  for (const filters::ParentWeighting& p : filters::CompareParentWeights(
           w.poses, parent.map, scan.measurements, context.sensor, params.map)) {
    w.single_cluster.push_back(p.single_cluster);
    w.rb_phd.push_back(p.rb_phd);
    w.log_single_cluster.push_back(p.log_single_cluster);
    w.log_rb_phd.push_back(p.log_rb_phd);
    w.missed_mass.push_back(p.log_rb_phd - p.log_single_cluster);
  }
  return w;
}

std::string ParentWeightsCsv(const ParentWeights& w) {
  const double norm_sc = LogSumExp(w.log_single_cluster);
  const double norm_rb = LogSumExp(w.log_rb_phd);
  std::string text =
      "parent,x,y,theta,sc_weight,rb_weight,sc_log_weight,rb_log_weight,missed_mass\n";
  for (std::size_t i = 0; i < w.poses.size(); ++i) {
    text += std::to_string(i) + "," + FormatNumber(w.poses[i].x()) + "," +
            FormatNumber(w.poses[i].y()) + "," + FormatNumber(w.poses[i].z()) + "," +
            FormatNumber(w.single_cluster[i]) + "," + FormatNumber(w.rb_phd[i]) + "," +
            FormatNumber(w.log_single_cluster[i] - norm_sc) + "," +
            FormatNumber(w.log_rb_phd[i] - norm_rb) + "," + FormatNumber(w.missed_mass[i]) + "\n";
  }
  return text;
}

nlohmann::json ParentWeightsJson(const ParentWeights& w) {
  nlohmann::json cov = nlohmann::json::array();
  for (int r = 0; r < 3; ++r)
    cov.push_back({w.predicted_cov(r, 0), w.predicted_cov(r, 1), w.predicted_cov(r, 2)});
  return {{"step", w.step},
          {"parents", w.poses.size()},
          {"measurements", w.measurements},
          {"map_components", w.map_components},
          {"previous_pose", PoseJson(w.previous_pose)},
          {"predicted_mean", PoseJson(w.predicted_mean)},
          {"predicted_cov", cov},
          {"spread", w.spread},
          {"true_pose", w.true_pose ? PoseJson(*w.true_pose) : nlohmann::json(nullptr)},
          {"ess_single_cluster", EffectiveSampleSize(w.single_cluster)},
          {"ess_rb_phd", EffectiveSampleSize(w.rb_phd)}};
}

}  // namespace phdslam::validation
