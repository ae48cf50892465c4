#include "reference/ceres/outlier_screening.h"

#include <Eigen/LU>
#include <limits>
#include <stdexcept>
#include <string>

#include "src/core/angles.h"
#include "src/models/range_bearing_model.h"

namespace phdslam::reference {

double MeasurementChi2(const Pose& x, const Landmark& m, const Measurement& z,
                       const Mat2& measurement_cov) {
  if ((m - x.head<2>()).squaredNorm() < 1e-18) return std::numeric_limits<double>::infinity();
  const Measurement z_hat = models::PredictMeasurement(x, m);
  const Vec2 e(z(0) - z_hat(0), WrapAngle(z(1) - z_hat(1)));
  return e.dot(measurement_cov.inverse() * e);
}

int DropOutlierMeasurements(const datasets::Scenario& scenario, const std::vector<Pose>& poses,
                            const std::vector<Landmark>& landmarks, double chi2,
                            Association* association) {
  if (!(chi2 > 0.0)) {
    throw std::invalid_argument("DropOutlierMeasurements: chi2 must be > 0, got " +
                                std::to_string(chi2));
  }
  if (association->size() > scenario.steps.size() || association->size() > poses.size()) {
    throw std::invalid_argument("DropOutlierMeasurements: association longer than the run");
  }
  std::vector<int> remaining = CountObservations(*association, landmarks.size());
  int dropped = 0;
  for (std::size_t k = 0; k < association->size(); ++k) {
    const std::vector<Measurement>& zs = scenario.steps[k].data.measurements;
    std::vector<int>& step = (*association)[k];
    if (step.size() != zs.size()) {
      throw std::invalid_argument("DropOutlierMeasurements: step " + std::to_string(k) + " has " +
                                  std::to_string(step.size()) + " labels for " +
                                  std::to_string(zs.size()) + " measurements");
    }
    for (std::size_t j = 0; j < zs.size(); ++j) {
      if (step[j] == kUnassociated) continue;
      const auto i = static_cast<std::size_t>(step[j]);
      if (remaining[i] <= 1) continue;
      if (MeasurementChi2(poses[k], landmarks[i], zs[j], scenario.sensor.noise_cov) <= chi2) {
        continue;
      }
      step[j] = kUnassociated;
      --remaining[i];
      ++dropped;
    }
  }
  return dropped;
}

}  // namespace phdslam::reference
