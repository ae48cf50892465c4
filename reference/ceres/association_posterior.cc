#include "reference/ceres/association_posterior.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/models/range_bearing_model.h"
#include "src/models/sensor_model.h"

namespace phdslam::reference {
namespace {

// 1/2 |r|^2 of one odometry factor between `from` and `to`.
double OdometryFactorCost(const ceres::CostFunction& factor, const Pose& from, const Pose& to) {
  const double* parameters[] = {from.data(), to.data()};
  Vec3 residual;
  if (!factor.Evaluate(parameters, residual.data(), nullptr)) {
    throw std::runtime_error("NegativeLogPosterior: an odometry factor could not be evaluated");
  }
  return 0.5 * residual.squaredNorm();
}

// The odometry term: the factors the graph holds (factor_graph.cc), the anchor standing for the
// pose before step 0 when step 0 is propagated.
double OdometryTerm(const datasets::Scenario& scenario, const OdometrySpec& odometry,
                    const std::vector<Pose>& poses) {
  double cost = 0.0;
  if ((*odometry.increments)[0].propagated) {
    const std::unique_ptr<ceres::CostFunction> factor(MakeOdometryCost(scenario, 0, odometry));
    cost += OdometryFactorCost(*factor, scenario.initial_pose, poses[0]);
  }
  for (std::size_t k = 1; k < poses.size(); ++k) {
    const std::unique_ptr<ceres::CostFunction> factor(MakeOdometryCost(scenario, k, odometry));
    cost += OdometryFactorCost(*factor, poses[k - 1], poses[k]);
  }
  return cost;
}

void CheckPosteriorInputs(const datasets::Scenario& scenario, const std::vector<Pose>& poses,
                          const std::vector<Landmark>& landmarks, const Association& association) {
  const std::size_t steps = scenario.steps.size();
  if (poses.size() != steps || association.size() != steps) {
    throw std::invalid_argument("NegativeLogPosterior: expected " + std::to_string(steps) +
                                " poses and association steps, got " +
                                std::to_string(poses.size()) + " and " +
                                std::to_string(association.size()));
  }
  for (std::size_t k = 0; k < steps; ++k) {
    if (association[k].size() != scenario.steps[k].data.measurements.size()) {
      throw std::invalid_argument("NegativeLogPosterior: step " + std::to_string(k) +
                                  " has a different number of associations and measurements");
    }
    for (int a : association[k]) {
      if (a != kUnassociated && (a < 0 || static_cast<std::size_t>(a) >= landmarks.size())) {
        throw std::invalid_argument("NegativeLogPosterior: step " + std::to_string(k) +
                                    " associates landmark " + std::to_string(a) + " of " +
                                    std::to_string(landmarks.size()));
      }
    }
  }
}

}  // namespace

void PosteriorOptions::Validate() const {
  if (!std::isfinite(birth_log_weight)) {
    throw std::invalid_argument("posterior_birth_log_weight must be finite");
  }
}

PosteriorTerms NegativeLogPosterior(const datasets::Scenario& scenario,
                                    const OdometrySpec& odometry, const std::vector<Pose>& poses,
                                    const std::vector<Landmark>& landmarks,
                                    const Association& association,
                                    const PosteriorOptions& options) {
  options.Validate();
  CheckPosteriorInputs(scenario, poses, landmarks, association);
  PosteriorTerms terms;
  if (options.map_prior == PosteriorMapPrior::kPoissonBirth) {
    terms.births = -static_cast<double>(landmarks.size()) * options.birth_log_weight;
  }
  if (poses.empty()) return terms;
  terms.odometry = OdometryTerm(scenario, odometry, poses);

  const Mat2& r = scenario.sensor.noise_cov;
  const double log_clutter = std::log(scenario.sensor.ClutterIntensity());
  std::vector<bool> detected(landmarks.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const models::FovView fov(scenario.sensor, poses[k]);
    const auto& measurements = scenario.steps[k].data.measurements;
    std::fill(detected.begin(), detected.end(), false);
    for (std::size_t j = 0; j < measurements.size(); ++j) {
      const int a = association[k][j];
      if (a == kUnassociated) {
        terms.clutter -= log_clutter;
        continue;
      }
      const auto i = static_cast<std::size_t>(a);
      detected[i] = true;
      Vec2 innovation = measurements[j] - models::PredictMeasurement(poses[k], landmarks[i]);
      innovation(1) = WrapAngle(innovation(1));
      const std::optional<double> log_likelihood = LogNormalPdf<2>(innovation, Vec2::Zero(), r);
      if (!log_likelihood) {
        throw std::invalid_argument(
            "NegativeLogPosterior: the sensor noise R is not positive "
            "definite");
      }
      terms.measurements -= *log_likelihood;
      terms.detections -= std::log(
          std::clamp(fov.DetectionProbability(landmarks[i]), kPosteriorMinPd, kPosteriorMaxPd));
    }
    for (std::size_t i = 0; i < landmarks.size(); ++i) {
      if (detected[i]) continue;
      const double pd = fov.DetectionProbability(landmarks[i]);
      if (pd > 0.0) terms.missed -= std::log1p(-std::min(pd, kPosteriorMaxPd));
    }
  }
  return terms;
}

}  // namespace phdslam::reference
