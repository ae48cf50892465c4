#include "src/filters/rb_phd_weighting.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "src/core/angles.h"
#include "src/core/gaussian.h"
#include "src/core/log_sum_exp.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::filters {
namespace {

double Mass(std::span<const phd::GaussianComponent> components) {
  double m = 0.0;
  for (const phd::GaussianComponent& c : components) m += std::exp(c.log_weight);
  return m;
}

double ClutterIntegral(const models::SensorModel& sensor) {
  return std::max(sensor.clutter_rate, models::SensorModel::kMinFilterClutterRate);
}

// ln kappa^Z + m_k - m_{k|k-1} - lambda: the factor both strategies share.
double SharedLogFactor(const PhdIntensityPair& v, std::span<const Measurement> measurements,
                       const models::SensorModel& sensor) {
  const double log_kappa = std::log(sensor.ClutterIntensity());
  return static_cast<double>(measurements.size()) * log_kappa + Mass(v.updated) -
         Mass(v.predicted) - ClutterIntegral(sensor);
}

// The highest-weight updated component detectable at the pose; nullptr when there is none.
const phd::GaussianComponent* EvaluationPoint(std::span<const phd::GaussianComponent> updated,
                                              const models::FovView& fov) {
  const phd::GaussianComponent* best = nullptr;
  for (const phd::GaussianComponent& c : updated) {
    if (fov.DetectionProbability(c.mean) <= 0.0) continue;
    if (best == nullptr || c.log_weight > best->log_weight) best = &c;
  }
  return best;
}

// ln v(m) over two lists.
double LogIntensityOfBothAt(std::span<const phd::GaussianComponent> a,
                            std::span<const phd::GaussianComponent> b, const Landmark& m) {
  return LogAddExp(filters::LogIntensityAt(a, m), filters::LogIntensityAt(b, m));
}

// ln[(1 - pD) + pD sum_z N(z; h(X, m), R) / kappa].
double LogSingleFeatureDetectionTerm(const Pose& pose, const Landmark& m, double pd,
                                     std::span<const Measurement> measurements,
                                     const models::SensorModel& sensor) {
  const double log_kappa = std::log(sensor.ClutterIntensity());
  const Measurement z_hat = models::PredictMeasurement(pose, m);
  std::vector<double> terms;
  terms.reserve(measurements.size() + 1);
  terms.push_back(pd < 1.0 ? std::log1p(-pd) : kNegInf);
  for (const Measurement& z : measurements) {
    Vec2 nu = z - z_hat;
    nu(1) = WrapAngle(nu(1));
    terms.push_back(std::log(pd) + EvalGaussian2(nu, sensor.noise_cov).log_pdf - log_kappa);
  }
  return LogSumExp(terms);
}

}  // namespace

double LogMass(std::span<const phd::GaussianComponent> components) {
  return std::log(Mass(components));
}

double LogIntensityAt(std::span<const phd::GaussianComponent> components, const Landmark& m) {
  std::vector<double> terms;
  terms.reserve(components.size());
  for (const phd::GaussianComponent& c : components) {
    const Gaussian2Eval e = EvalGaussian2(m - c.mean, c.cov);
    terms.push_back(c.log_weight + e.log_pdf);
  }
  return LogSumExp(terms);
}

double EmptyMapLogWeight(const PhdIntensityPair& v, std::span<const Measurement> measurements,
                         const models::SensorModel& sensor) {
  return SharedLogFactor(v, measurements, sensor);
}

double SingleFeatureLogWeight(const PhdIntensityPair& v, const Pose& pose,
                              std::span<const Measurement> measurements,
                              const models::SensorModel& sensor) {
  const models::FovView fov(sensor, pose);
  const phd::GaussianComponent* point = EvaluationPoint(v.updated, fov);
  if (point == nullptr) return EmptyMapLogWeight(v, measurements, sensor);
  const Landmark m = point->mean;
  const double pd = fov.DetectionProbability(m);
  return SharedLogFactor(v, measurements, sensor) +
         LogSingleFeatureDetectionTerm(pose, m, pd, measurements, sensor) +
         LogIntensityOfBothAt(v.predicted, v.passive, m) -
         LogIntensityOfBothAt(v.updated, v.passive, m);
}

double RbPhdLogWeight(RbPhdWeighting weighting, double paper46_log_likelihood,
                      const PhdIntensityPair& v, const Pose& pose,
                      std::span<const Measurement> measurements,
                      const models::SensorModel& sensor) {
  switch (weighting) {
    case RbPhdWeighting::kEmptyMap:
      return EmptyMapLogWeight(v, measurements, sensor);
    case RbPhdWeighting::kSingleFeature:
      return SingleFeatureLogWeight(v, pose, measurements, sensor);
    case RbPhdWeighting::kPaper46:
      break;
  }
  return paper46_log_likelihood;
}

}  // namespace phdslam::filters
