#include "src/filters/sc_phd_slam.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/filters/particle_estimate.h"
#include "src/filters/resampling.h"
#include "src/models/pose_propagation.h"
#include "src/models/sensor_model.h"

namespace phdslam::filters {
namespace {

/// A factor L with L L^T = Q for a symmetric positive semi-definite Q (eigen-decomposition, so a
/// singular Q such as zero noise is allowed). Throws naming `what` otherwise.
template <int N>
Eigen::Matrix<double, N, N> PsdFactor(const Eigen::Matrix<double, N, N>& q,
                                      const std::string& what) {
  const double scale = std::max(1.0, q.cwiseAbs().maxCoeff());
  if (!q.allFinite() || (q - q.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale) {
    throw std::invalid_argument("ScPhdSlam: " + what + " must be finite and symmetric");
  }
  if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>>(q).eigenvalues().minCoeff() <
      -1e-12 * scale) {
    throw std::invalid_argument("ScPhdSlam: " + what + " must be positive semi-definite");
  }
  return PsdSquareRoot<N>(q);
}

}  // namespace

double UpdateDaughterMap(phd::GmPhdMap& map, const Pose& pose,
                         std::span<const Measurement> measurements,
                         const models::SensorModel& sensor, const phd::MapParams& params,
                         bool empty_scan_update, std::vector<int>* ungated, InnovationStats* nis) {
  if (ungated != nullptr) ungated->clear();
  if (nis != nullptr) *nis = InnovationStats{};
  if (!measurements.empty()) {
    phd::PhdUpdateResult result = map.Update(pose, measurements, sensor, params);
    if (ungated != nullptr) *ungated = std::move(result.ungated);
    if (nis != nullptr) *nis = InnovationStats{result.nis_sum, result.nis_count};
    return result.log_likelihood;
  }
  if (!empty_scan_update) return 0.0;
  // No measurements: every component is missed, w <- (1 - pD) w, likelihood exp(-sum pD w).
  std::vector<phd::GaussianComponent> components = map.active();
  const models::FovView fov(sensor, pose);
  double missed_mass = 0.0;
  for (phd::GaussianComponent& c : components) {
    const double pd = fov.DetectionProbability(c.mean);
    if (pd <= 0.0) continue;
    missed_mass += pd * std::exp(c.log_weight);
    c.log_weight += std::log1p(-pd);
  }
  map.SetActive(std::move(components));
  return params.reference_omit_missed_detection_mass ? 0.0 : -missed_mass;
}

std::vector<phd::GaussianComponent> CardinalityMapEstimate(const phd::GmPhdMap& map) {
  std::vector<phd::GaussianComponent> all = map.active();
  const std::vector<phd::GaussianComponent> passive = map.passive();
  all.insert(all.end(), passive.begin(), passive.end());
  double cardinality = 0.0;
  for (const phd::GaussianComponent& c : all) cardinality += std::exp(c.log_weight);
  const auto count = std::min<std::size_t>(
      all.size(), static_cast<std::size_t>(std::max(0L, std::lround(cardinality))));
  std::stable_sort(all.begin(), all.end(),
                   [](const phd::GaussianComponent& a, const phd::GaussianComponent& b) {
                     return a.log_weight > b.log_weight;
                   });
  all.resize(count);
  return all;
}

ScPhdSlam::ScPhdSlam(EstimatorContext context, ScPhdSlamParams params, std::uint64_t stream_seed)
    : context_(std::move(context)), params_(std::move(params)), rng_(stream_seed) {
  if (params_.particles < 1) {
    throw std::invalid_argument("ScPhdSlam: particles must be >= 1, got " +
                                std::to_string(params_.particles));
  }
  if (params_.shotgun < 1) {
    throw std::invalid_argument("ScPhdSlam: shotgun must be >= 1, got " +
                                std::to_string(params_.shotgun));
  }
  if (context_.motion == nullptr) throw std::invalid_argument("ScPhdSlam: no motion model");
  control_noise_sqrt_ = PsdFactor<2>(context_.control_noise_cov, "control noise covariance Q_u");
  regularisation_sqrt_ = PsdFactor<3>(params_.pose_regularisation, "pose_regularisation Q_n");
  parents_.resize(params_.particles);
  for (ScParent& p : parents_) {
    p.pose = context_.initial_pose;
    p.log_weight = -std::log(static_cast<double>(params_.particles));
  }
}

Pose ScPhdSlam::SamplePose(const Pose& pose, const StepData& step,
                           std::span<const double> xi) const {
  const Vec3 xi_pose(xi[0], xi[1], xi[2]);
  const std::size_t intervals = step.times.size() - 1;
  if (params_.prediction == ScPredictionSampling::kControlNoise) {
    Pose x = pose + regularisation_sqrt_ * xi_pose;
    for (std::size_t i = 0; i < intervals; ++i) {
      const double dt = step.times[i + 1] - step.times[i];
      const Control u = step.controls[i] + control_noise_sqrt_ * Vec2(xi[3 + 2 * i], xi[4 + 2 * i]);
      x = context_.motion->Predict(x, u, dt);
    }
    return x;
  }
  // Linearised Gaussian, as the RB-PHD-SLAM family propagates it, then one draw.
  const PoseMoments predicted = LinearisedPrediction(pose, step);
  const auto chol = CholeskyLower<3>(predicted.cov);
  return chol ? Pose(predicted.mean + *chol * xi_pose) : predicted.mean;
}

PoseMoments ScPhdSlam::LinearisedPrediction(const Pose& pose, const StepData& step) const {
  PoseMoments predicted{0.0, pose, params_.pose_regularisation};
  models::PropagatePoseGaussian(*context_.motion, context_.control_noise_cov, step, predicted.mean,
                                predicted.cov);
  return predicted;
}

std::optional<PoseMoments> ScPhdSlam::PredictedMixtureMoments(const StepData& step) const {
  if (step.times.size() < 2) return std::nullopt;
  std::vector<PoseMoments> components;
  components.reserve(parents_.size());
  for (const ScParent& p : parents_) {
    PoseMoments m = LinearisedPrediction(p.pose, step);
    m.log_weight = p.log_weight;
    components.push_back(m);
  }
  return MatchMoments(components);
}

StepOutput ScPhdSlam::Step(const StepData& step) {
  if (step.times.empty()) throw std::invalid_argument("ScPhdSlam::Step: step has no time stamps");
  const std::size_t intervals = step.times.size() - 1;
  if (step.controls.size() < intervals) {
    throw std::invalid_argument("ScPhdSlam::Step: " + std::to_string(step.times.size()) +
                                " time stamps need " + std::to_string(intervals) +
                                " controls, got " + std::to_string(step.controls.size()));
  }
  const int num_parents = static_cast<int>(parents_.size());
  // Without propagation every copy of a parent would be identical: one child per parent.
  const int copies = intervals > 0 ? params_.shotgun : 1;
  const std::size_t per_child = intervals > 0 ? 3 + 2 * intervals : 0;

  // The step's random numbers, child by child (parent-major), drawn before anything else.
  std::vector<double> normals(static_cast<std::size_t>(num_parents) * copies * per_child);
  for (double& v : normals) v = rng_.Normal();

  const std::optional<PoseMoments> rb = PredictedMixtureMoments(step);

  // 1. Births from the previous step's measurements at the pose they were taken from.
  for (ScParent& p : parents_) {
    if (p.births.empty()) continue;
    p.map.AddBirths(p.pose, p.births, context_.sensor.noise_cov, params_.map);
    p.births.clear();
  }

  // 2-3. Shotgun prediction, daughter update and single-cluster weight of every child.
  std::vector<ScParent> children;
  children.reserve(static_cast<std::size_t>(num_parents) * copies);
  children_.clear();
  std::vector<int> ungated;
  for (int i = 0; i < num_parents; ++i) {
    ScParent& parent = parents_[i];
    for (int c = 0; c < copies; ++c) {
      ScParent child;
      const std::size_t offset = children.size() * per_child;
      child.pose = intervals > 0
                       ? SamplePose(parent.pose, step,
                                    std::span<const double>(normals).subspan(offset, per_child))
                       : parent.pose;
      if (c + 1 < copies) {
        child.map = parent.map;
      } else {
        child.map = std::move(parent.map);  // the last copy takes the parent's map
      }
      child.log_weight =
          parent.log_weight + UpdateDaughterMap(child.map, child.pose, step.measurements,
                                                context_.sensor, params_.map,
                                                params_.empty_scan_update, &ungated, &child.nis);
      child.births.reserve(ungated.size());
      for (int j : ungated) child.births.push_back(step.measurements[j]);
      children_.push_back({i, child.pose, child.log_weight, false});
      children.push_back(std::move(child));
    }
  }

  // 4. Keep the N highest-weight children (lower child index first on ties), in child order.
  std::vector<int> order(children.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return children[a].log_weight > children[b].log_weight; });
  const int keep = params_.particles;
  order.resize(std::min<std::size_t>(order.size(), keep));
  std::sort(order.begin(), order.end());
  std::vector<ScParent> next;
  next.reserve(order.size());
  for (int k : order) {
    children_[k].kept = true;
    next.push_back(std::move(children[k]));
  }
  parents_ = std::move(next);
  std::vector<double> log_w;
  log_w.reserve(parents_.size());
  for (const ScParent& p : parents_) log_w.push_back(p.log_weight);
  const double log_total = LogSumExp(log_w);
  for (ScParent& p : parents_) p.log_weight -= log_total;

  // 5. Map reduction at each survivor's pose.
  for (ScParent& p : parents_) p.map.Reduce(p.pose, context_.sensor, params_.map);

  // 6. Estimates.
  const std::vector<double> w = NormalisedWeights(log_w);
  StepOutput out;
  out.pose.setZero();
  for (std::size_t i = 0; i < parents_.size(); ++i) out.pose += w[i] * parents_[i].pose;
  best_ = static_cast<int>(
      HighestWeightIndex(parents_, [](const ScParent& p) { return p.log_weight; }));
  if (parents_.size() > 1) {
    out.pose_cov = WeightedSpread(parents_, w, out.pose,
                                  [](const ScParent& p) -> const Pose& { return p.pose; });
  }
  last_map_ = CardinalityMapEstimate(parents_[best_].map);
  out.diag.ess = parents_.size() == 1 ? 1.0 : EffectiveSampleSize(w);
  out.diag.resampled = false;
  out.diag.hypotheses = copies;
  out.diag.map_components = static_cast<int>(parents_[best_].map.size());
  out.diag.nis_sum = parents_[best_].nis.nis_sum;
  out.diag.nis_count = parents_[best_].nis.count;
  if (rb) {
    out.pose_mean_rb = rb->mean;
    out.pose_cov_rb = rb->cov;
  }
  return out;
}

MapEstimate ScPhdSlam::Map() const {
  MapEstimate m;
  for (const phd::GaussianComponent& c : last_map_) {
    m.means.push_back(c.mean);
    m.covs.push_back(c.cov);
    m.log_weights.push_back(c.log_weight);
  }
  return m;
}

}  // namespace phdslam::filters
