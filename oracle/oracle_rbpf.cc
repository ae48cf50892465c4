#include "oracle/oracle_rbpf.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "oracle/known_association_density.h"
#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::oracle {
namespace {

// Checks the labels and returns the number of landmark slots (largest index + 1).
int CheckOrigins(const std::vector<std::vector<int>>& origins) {
  int max_index = -1;
  for (std::size_t k = 0; k < origins.size(); ++k) {
    std::vector<int> seen;
    for (std::size_t j = 0; j < origins[k].size(); ++j) {
      const int o = origins[k][j];
      if (o < datasets::kClutter) {
        throw std::invalid_argument(
            "oracle RBPF: step " + std::to_string(k) + ", measurement " + std::to_string(j) +
            ": origin label " + std::to_string(o) +
            " is not a landmark index (>= 0) or clutter (-1); the oracle needs known "
            "origins and cannot run on real data such as Victoria Park");
      }
      if (o >= 0) seen.push_back(o);
      max_index = std::max(max_index, o);
    }
    std::sort(seen.begin(), seen.end());
    const auto dup = std::adjacent_find(seen.begin(), seen.end());
    if (dup != seen.end()) {
      throw std::invalid_argument("oracle RBPF: step " + std::to_string(k) + " measures landmark " +
                                  std::to_string(*dup) +
                                  " more than once; expected at most one measurement per "
                                  "landmark and scan");
    }
  }
  return max_index + 1;
}

}  // namespace

void OracleParams::Validate() const {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("oracle parameters: " + what);
  };
  if (particles < 1) fail("particles must be >= 1, got " + std::to_string(particles));
  if (!(ess_threshold >= 0.0) || !std::isfinite(ess_threshold)) {
    fail("ess_threshold must be finite and >= 0, got " + std::to_string(ess_threshold));
  }
  if (ipl_iterations < 1) {
    fail("ipl_iterations must be >= 1, got " + std::to_string(ipl_iterations));
  }
  if (!(ipl_kl_tolerance >= 0.0) || !std::isfinite(ipl_kl_tolerance)) {
    fail("ipl_kl_tolerance must be finite and >= 0, got " + std::to_string(ipl_kl_tolerance));
  }
  if (!pose_regularisation.allFinite() ||
      !pose_regularisation.isApprox(pose_regularisation.transpose(), 0.0)) {
    fail("pose_regularisation must be finite and symmetric");
  }
}

OracleMapModel::OracleMapModel(std::vector<std::vector<int>> origins, const Mat2& measurement_noise)
    : origins_(std::move(origins)), noise_cov_(measurement_noise) {
  landmark_slots_ = CheckOrigins(origins_);
}

OracleMapModel::Map OracleMapModel::InitialMap() const {
  Map m;
  m.landmarks.resize(landmark_slots_);
  return m;
}

void OracleMapModel::BeginStep(const StepData& step) {
  if (step_index_ >= origins_.size()) {
    throw std::invalid_argument("oracle RBPF: step " + std::to_string(step_index_) +
                                " has no origin labels (only " + std::to_string(origins_.size()) +
                                " steps were given)");
  }
  const std::vector<int>& origin = origins_[step_index_];
  if (origin.size() != step.measurements.size()) {
    throw std::invalid_argument("oracle RBPF: step " + std::to_string(step_index_) + " has " +
                                std::to_string(step.measurements.size()) + " measurements but " +
                                std::to_string(origin.size()) + " origin labels");
  }
  ++step_index_;
  origin_ = &origin;
  // Landmark measurements in ascending landmark order (the IPL's sequential order).
  by_landmark_.clear();
  for (int j = 0; j < static_cast<int>(origin.size()); ++j) {
    if (origin[j] >= 0) by_landmark_.push_back(j);
  }
  std::sort(by_landmark_.begin(), by_landmark_.end(),
            [&origin](int a, int b) { return origin[a] < origin[b]; });
}

filters::MapView OracleMapModel::View(const Map& map) {
  view_.clear();
  view_association_.assign(origin_->size(), -1);
  for (int j : by_landmark_) {
    const OracleLandmark& lm = map.landmarks[(*origin_)[j]];
    if (!lm.seen) continue;
    view_association_[j] = static_cast<int>(view_.size());
    view_.push_back({lm.mean, lm.cov, 0.0});
  }
  return {view_, view_association_};
}

void OracleMapModel::Update(Map& map, const Pose& pose, const StepData& step, double& log_weight,
                            filters::InnovationStats& nis) const {
  const std::vector<int>& origin = *origin_;
  // Landmark likelihoods and EKF updates at the sampled pose, then first sightings.
  for (int j : by_landmark_) {
    OracleLandmark& lm = map.landmarks[origin[j]];
    if (!lm.seen) continue;
    const auto jac = models::MeasurementJacobians(pose, lm.mean);
    Vec2 nu = step.measurements[j] - models::PredictMeasurement(pose, lm.mean);
    nu(1) = WrapAngle(nu(1));
    const Mat2 pht = lm.cov * jac.hm.transpose();
    Mat2 s = jac.hm * pht + noise_cov_;
    Symmetrize(s);
    const auto log_lik = LogNormalPdf<2>(nu, Vec2::Zero(), s);
    if (log_lik) log_weight += *log_lik;
    nis.Add(nu, s);
    const Mat2 k = pht * s.inverse();
    lm.mean += k * nu;
    lm.cov -= k * s * k.transpose();
    Symmetrize(lm.cov);
  }
  for (int j : by_landmark_) {
    OracleLandmark& lm = map.landmarks[origin[j]];
    if (lm.seen) continue;
    lm.mean = models::InverseMeasurement(pose, step.measurements[j]);
    lm.cov = models::BirthCovariance(pose, step.measurements[j], noise_cov_);
    lm.seen = true;
  }
}

filters::MapEstimate OracleMapModel::ToMapEstimate(const Snapshot& snapshot) const {
  filters::MapEstimate m;
  for (const OracleLandmark& lm : snapshot) {
    if (!lm.seen) continue;
    m.means.push_back(lm.mean);
    m.covs.push_back(lm.cov);
    m.log_weights.push_back(0.0);
  }
  return m;
}

int OracleMapModel::ComponentCount(const Map& map) const {
  return static_cast<int>(std::count_if(map.landmarks.begin(), map.landmarks.end(),
                                        [](const OracleLandmark& lm) { return lm.seen; }));
}

std::unique_ptr<OracleRbpf> MakeKnownAssociationFilter(
    filters::EstimatorContext context, std::vector<std::vector<int>> origins,
    const OracleParams& params, std::unique_ptr<filters::ImportanceDensity> density,
    std::uint64_t stream_seed) {
  params.Validate();
  if (!context.motion) throw std::invalid_argument("oracle RBPF: the context has no motion model");
  OracleMapModel model(std::move(origins), context.sensor.noise_cov);
  filters::ParticleFilterParams skeleton;
  skeleton.particles = params.particles;
  skeleton.resampling = params.resampling;
  skeleton.ess_threshold_kind = filters::EssThresholdKind::kRelative;
  skeleton.ess_threshold = params.ess_threshold;
  skeleton.pose_regularisation = params.pose_regularisation;
  skeleton.reuse_parent_proposal = false;
  skeleton.draw_streams = params.draw_streams;
  return std::make_unique<OracleRbpf>(std::move(context), skeleton, std::move(model),
                                      std::move(density), stream_seed);
}

std::unique_ptr<OracleRbpf> MakeOracle(filters::EstimatorContext context,
                                       std::vector<std::vector<int>> origins,
                                       const OracleParams& params, std::uint64_t stream_seed) {
  auto density = std::make_unique<KnownAssociationIplDensity>(
      filters::IplOptions{params.ipl_iterations, params.ipl_kl_tolerance});
  return MakeKnownAssociationFilter(std::move(context), std::move(origins), params,
                                    std::move(density), stream_seed);
}

std::vector<std::vector<int>> ScenarioOrigins(const datasets::Scenario& scenario) {
  std::vector<std::vector<int>> origins;
  origins.reserve(scenario.steps.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    const datasets::ScenarioStep& s = scenario.steps[k];
    if (s.origin.size() != s.data.measurements.size()) {
      throw std::invalid_argument(
          "oracle RBPF: scenario '" + scenario.name + "' step " + std::to_string(k) + " has " +
          std::to_string(s.data.measurements.size()) + " measurements but " +
          std::to_string(s.origin.size()) + " origin labels; the oracle needs every origin");
    }
    origins.push_back(s.origin);
  }
  return origins;
}

std::unique_ptr<OracleRbpf> MakeOracle(const datasets::Scenario& scenario,
                                       const OracleParams& params, std::uint64_t stream_seed) {
  std::vector<std::vector<int>> origins = ScenarioOrigins(scenario);
  try {
    return MakeOracle(scenario.PublicContext(), std::move(origins), params, stream_seed);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("scenario '" + scenario.name + "': " + e.what());
  }
}

}  // namespace phdslam::oracle

template class phdslam::filters::ParticleFilter<phdslam::oracle::OracleMapModel>;
