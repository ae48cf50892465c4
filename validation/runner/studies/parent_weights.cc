#include "validation/runner/studies/parent_weights.h"

#include <cmath>
#include <stdexcept>

#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/core/random.h"
#include "src/filters/estimator.h"
#include "src/filters/pose_prediction.h"
#include "src/filters/rb_phd_weighting.h"
#include "src/filters/resampling.h"
#include "src/filters/sc_phd_slam.h"
#include "validation/runner/evaluation/wilcoxon.h"
#include "validation/runner/io/results_io.h"
#include "validation/runner/registry/scenario_defaults.h"

namespace phdslam::validation {
namespace {

double EffectiveSampleSize(const std::vector<double>& w) {
  double sum_sq = 0.0;
  for (double v : w) sum_sq += v * v;
  return sum_sq > 0.0 ? 1.0 / sum_sq : 0.0;
}

nlohmann::json PoseJson(const Pose& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

std::vector<ParentWeighting> CompareParentWeights(std::span<const Pose> parent_poses,
                                                  const phd::GmPhdMap& predicted_map,
                                                  std::span<const Measurement> measurements,
                                                  const models::SensorModel& sensor,
                                                  const phd::MapParams& params) {
  phd::MapParams single_cluster = params;
  single_cluster.reference_omit_missed_detection_mass = false;
  phd::MapParams rb_phd = params;
  rb_phd.reference_omit_missed_detection_mass = true;
  std::vector<double> log_sc;
  std::vector<double> log_rb;
  std::vector<double> log_sf;
  for (const Pose& x : parent_poses) {
    phd::GmPhdMap a = predicted_map;
    log_sc.push_back(
        filters::UpdateDaughterMap(a, x, measurements, sensor, single_cluster, true, nullptr));
    phd::GmPhdMap b = predicted_map;
    log_rb.push_back(filters::UpdateDaughterMap(b, x, measurements, sensor, rb_phd, true, nullptr));
    const std::vector<phd::GaussianComponent> passive = b.passive();
    const filters::PhdIntensityPair v{predicted_map.active(), b.active(), passive};
    log_sf.push_back(filters::SingleFeatureLogWeight(v, x, measurements, sensor));
  }
  const std::vector<double> w_sc = filters::NormalisedWeights(log_sc);
  const std::vector<double> w_rb = filters::NormalisedWeights(log_rb);
  const std::vector<double> w_sf = filters::NormalisedWeights(log_sf);
  std::vector<ParentWeighting> out(w_sc.size());
  for (std::size_t i = 0; i < w_sc.size(); ++i) {
    out[i] = {w_sc[i], w_rb[i], log_sc[i], log_rb[i], w_sf[i], log_sf[i]};
  }
  return out;
}

namespace {

void CheckDraws(const ParentWeightsSettings& settings) {
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
}

void CheckStep(const datasets::Scenario& scenario, std::size_t k) {
  if (k == 0 || k >= scenario.steps.size()) {
    throw std::invalid_argument("parent weights: step must be in 1.." +
                                std::to_string(scenario.steps.size() - 1) + ", got " +
                                std::to_string(k));
  }
}

filters::ScPhdSlamParams OneParentParams(const datasets::Scenario& scenario) {
  filters::ScPhdSlamParams params;
  filters::ApplyJson(ScenarioParameterDefaults(scenario.name, "scphd"), params);
  params.particles = 1;
  return params;
}

// The comparison at step k from the filter's best parent of step k - 1.
ParentWeights WeighParents(const datasets::Scenario& scenario, std::size_t k,
                           const filters::ScParent& parent, const filters::ScPhdSlamParams& params,
                           const ParentWeightsSettings& settings, std::uint64_t draw_seed) {
  const filters::EstimatorContext context = scenario.PublicContext();
  const datasets::StepData& scan = scenario.steps[k].data;
  ParentWeights w;
  w.step = k;
  w.previous_pose = parent.pose;
  w.predicted_mean = parent.pose;
  filters::PredictPoseGaussian(context, scan, params.pose_regularisation, w.predicted_mean,
                               w.predicted_cov);
  if (scenario.truth.poses.size() == scenario.steps.size()) w.true_pose = scenario.truth.poses[k];
  w.measurements = scan.measurements.size();
  w.map_components = parent.map.size();

  RandomStream rng(draw_seed);
  w.spread = settings.spread;
  // The predicted covariance is nearly singular in the heading (Q_n's 1e-18), where a Cholesky
  // may fail: an eigen-decomposition square root has no such case.
  const Mat3 root = settings.spread * PsdSquareRoot<3>(w.predicted_cov);
  w.poses.reserve(static_cast<std::size_t>(settings.parents));
  for (int i = 0; i < settings.parents; ++i) {
    const Vec3 xi(rng.Normal(), rng.Normal(), rng.Normal());
    w.poses.push_back(w.predicted_mean + root * xi);
  }
  for (const ParentWeighting& p :
       CompareParentWeights(w.poses, parent.map, scan.measurements, context.sensor, params.map)) {
    w.single_cluster.push_back(p.single_cluster);
    w.rb_phd.push_back(p.rb_phd);
    w.log_single_cluster.push_back(p.log_single_cluster);
    w.log_rb_phd.push_back(p.log_rb_phd);
    w.missed_mass.push_back(p.log_rb_phd - p.log_single_cluster);
    w.single_feature.push_back(p.single_feature);
    w.log_single_feature.push_back(p.log_single_feature);
  }
  return w;
}

}  // namespace

ParentWeights CompareParentWeightingAtStep(const datasets::Scenario& scenario,
                                           const ParentWeightsSettings& settings) {
  const std::size_t k = settings.step;
  CheckStep(scenario, k);
  CheckDraws(settings);
  const datasets::StepData& scan = scenario.steps[k].data;
  if (scan.measurements.empty()) {
    throw std::invalid_argument("parent weights: step " + std::to_string(k) +
                                " has no measurements; choose another --step");
  }
  const filters::ScPhdSlamParams params = OneParentParams(scenario);
  filters::ScPhdSlam filter(scenario.PublicContext(), params, DeriveSeed(settings.stream_seed, 1));
  for (std::size_t j = 0; j < k; ++j) filter.Step(scenario.steps[j].data);
  return WeighParents(scenario, k, filter.parents()[filter.best_parent()], params, settings,
                      DeriveSeed(settings.stream_seed, 2));
}

std::vector<StepEss> CompareParentWeightingOverSteps(const datasets::Scenario& scenario,
                                                     const ParentWeightsSettings& settings,
                                                     const std::vector<std::size_t>& steps) {
  CheckDraws(settings);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    CheckStep(scenario, steps[i]);
    if (i > 0 && steps[i] <= steps[i - 1]) {
      throw std::invalid_argument("parent weights: steps must increase");
    }
  }
  const filters::ScPhdSlamParams params = OneParentParams(scenario);
  filters::ScPhdSlam filter(scenario.PublicContext(), params, DeriveSeed(settings.stream_seed, 1));
  std::vector<StepEss> rows;
  std::size_t done = 0;
  const std::uint64_t draws = DeriveSeed(settings.stream_seed, 3);
  for (std::size_t k : steps) {
    for (; done < k; ++done) filter.Step(scenario.steps[done].data);
    if (scenario.steps[k].data.measurements.empty()) continue;
    const ParentWeights w = WeighParents(scenario, k, filter.parents()[filter.best_parent()],
                                         params, settings, DeriveSeed(draws, k));
    rows.push_back({k, w.measurements, w.map_components, EffectiveSampleSize(w.single_cluster),
                    EffectiveSampleSize(w.rb_phd), EffectiveSampleSize(w.single_feature)});
  }
  return rows;
}

std::string StepEssCsv(const std::vector<StepEss>& rows) {
  std::string text =
      "step,measurements,map_components,ess_single_cluster,ess_rb_phd,ess_single_feature\n";
  for (const StepEss& r : rows) {
    text += std::to_string(r.step) + "," + std::to_string(r.measurements) + "," +
            std::to_string(r.map_components) + "," + FormatNumber(r.single_cluster) + "," +
            FormatNumber(r.rb_phd) + "," + FormatNumber(r.single_feature) + "\n";
  }
  return text;
}

namespace {

nlohmann::json PairedJson(const std::vector<double>& differences) {
  const WilcoxonResult t = WilcoxonSignedRank(differences);
  double mean = 0.0;
  for (double d : differences) mean += d;
  if (!differences.empty()) mean /= static_cast<double>(differences.size());
  return {{"mean_difference", mean},
          {"n", t.n},
          {"n_nonzero", t.n_nonzero},
          {"w_plus", t.w_plus},
          {"w_minus", t.w_minus},
          {"p_value", t.p_value ? nlohmann::json(*t.p_value) : nlohmann::json(nullptr)}};
}

}  // namespace

nlohmann::json StepEssJson(const std::vector<StepEss>& rows) {
  double sc = 0.0;
  double rb = 0.0;
  double sf = 0.0;
  std::vector<double> sc_minus_sf;
  std::vector<double> sc_minus_rb;
  for (const StepEss& r : rows) {
    sc += r.single_cluster;
    rb += r.rb_phd;
    sf += r.single_feature;
    sc_minus_sf.push_back(r.single_cluster - r.single_feature);
    sc_minus_rb.push_back(r.single_cluster - r.rb_phd);
  }
  const double n = rows.empty() ? 1.0 : static_cast<double>(rows.size());
  return {{"steps", rows.size()},
          {"mean_ess_single_cluster", sc / n},
          {"mean_ess_rb_phd", rb / n},
          {"mean_ess_single_feature", sf / n},
          {"single_cluster_minus_single_feature", PairedJson(sc_minus_sf)},
          {"single_cluster_minus_rb_phd", PairedJson(sc_minus_rb)}};
}

std::string ParentWeightsCsv(const ParentWeights& w) {
  const double norm_sc = LogSumExp(w.log_single_cluster);
  const double norm_rb = LogSumExp(w.log_rb_phd);
  const double norm_sf = LogSumExp(w.log_single_feature);
  std::string text =
      "parent,x,y,theta,sc_weight,rb_weight,sc_log_weight,rb_log_weight,missed_mass,sf_weight,"
      "sf_log_weight\n";
  for (std::size_t i = 0; i < w.poses.size(); ++i) {
    text += std::to_string(i) + "," + FormatNumber(w.poses[i].x()) + "," +
            FormatNumber(w.poses[i].y()) + "," + FormatNumber(w.poses[i].z()) + "," +
            FormatNumber(w.single_cluster[i]) + "," + FormatNumber(w.rb_phd[i]) + "," +
            FormatNumber(w.log_single_cluster[i] - norm_sc) + "," +
            FormatNumber(w.log_rb_phd[i] - norm_rb) + "," + FormatNumber(w.missed_mass[i]) + "," +
            FormatNumber(w.single_feature[i]) + "," +
            FormatNumber(w.log_single_feature[i] - norm_sf) + "\n";
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
          {"ess_rb_phd", EffectiveSampleSize(w.rb_phd)},
          {"ess_single_feature", EffectiveSampleSize(w.single_feature)}};
}

}  // namespace phdslam::validation
